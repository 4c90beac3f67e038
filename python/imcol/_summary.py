# SPDX-License-Identifier: BSD-3-Clause
"""A run's summary (summary.json) as typed attributes: result.solver.steps, result.contact.law, result.flow.ms_per_step.

Each block is a read-only view of its part of the summary. A name the block declares (with its type below) and the
run did not write reads None (result.flow of a run without the flow kernel); a name neither declared nor written
raises AttributeError. Blocks whose keys are data (e_measures, model, measures_disagree, run) stay dicts.
"""
from typing import Any, Dict, List, Optional


# One class (61 lines): the attribute protocol (getattr, dir, repr, to_dict) over one JSON object reads best in one place.
class Block:
    """Attributes over one JSON object of the summary; to_dict() gives the object back."""

    _blocks: Dict[str, type] = {}  # name -> Block class of a nested object, or of each element of a list of objects
    __slots__ = ("_d",)

    def __init__(self, d: Dict[str, Any]):
        object.__setattr__(self, "_d", d)

    @classmethod
    def _declared(cls) -> List[str]:
        """The names this class declares (its annotations), computed once per class."""
        if "_names" not in cls.__dict__:
            names: List[str] = []
            for c in reversed(cls.__mro__):
                names += [n for n in c.__dict__.get("__annotations__", {}) if not n.startswith("_") and n not in names]
            cls._names = names
        return cls.__dict__["_names"]

    def __getattr__(self, name: str) -> Any:
        d = object.__getattribute__(self, "_d")
        if name in d:
            v = d[name]
            cls = type(self)._blocks.get(name, Block)
            if isinstance(v, dict) and name not in type(self)._plain:
                return cls(v)
            if isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
                return [cls(x) for x in v]
            return v
        if name in type(self)._declared():
            return None
        raise AttributeError(f"{type(self).__name__} has no attribute '{name}'")

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError("a run's summary is read-only")

    def __dir__(self) -> List[str]:
        d = object.__getattribute__(self, "_d")
        return sorted(set(self._declared()) | {k for k in d if k.isidentifier()} | {"to_dict"})

    def __getitem__(self, key: str) -> Any:  # keys that are not identifiers ("drag.law")
        return object.__getattribute__(self, "_d")[key]

    def __contains__(self, key: str) -> bool:
        return key in object.__getattribute__(self, "_d")

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Block) and self.to_dict() == other.to_dict()

    __hash__ = None  # type: ignore[assignment]

    def to_dict(self) -> Dict[str, Any]:
        """This block as summary.json writes it (a copy)."""
        import copy
        return copy.deepcopy(object.__getattribute__(self, "_d"))

    def __repr__(self) -> str:
        d = object.__getattribute__(self, "_d")
        inner = ", ".join(f"{k}={v!r}" for k, v in d.items() if not isinstance(v, (dict, list)))
        return f"{type(self).__name__}({inner})"

    _plain: frozenset = frozenset()  # nested objects kept as dicts (their keys are data, not names)


class Fluid(Block):
    name: Optional[str]
    mass_fraction: Optional[float]
    temperature_C: Optional[float]
    density_kg_m3: float
    viscosity_Pa_s: float
    density_source: str
    viscosity_source: str


class Velocities(Block):
    """Fitted impact and rebound velocities, m/s."""
    U_i1: Optional[float]
    U_i2: Optional[float]
    U_r1: Optional[float]
    U_r2: Optional[float]


class Bounce(Block):
    """One contact (summary.json `bounces`)."""
    contact: int
    t_contact_s: float
    t_separation_s: Optional[float]
    e: Optional[float]
    e_is: str
    e_instant: Optional[float]
    impact_velocity_m_s: Optional[float]
    rebound_velocity_m_s: Optional[float]
    impact_speed_at_delta_ss_m_s: Optional[float]
    apex_gap_m: Optional[float]
    t_apex_s: Optional[float]
    e_measures: Dict[str, Dict[str, Any]]
    measures_disagree: Dict[str, float]
    energy_budget: Optional[Dict[str, Any]]
    _plain = frozenset({"e_measures", "measures_disagree", "energy_budget"})


class Contact(Block):
    """The contact law and the first contact; a law's own numbers (W_o_N, beta, …) are attributes too."""
    law: str
    t_contact_s: Optional[float]
    t_separation_s: Optional[float]
    impact_speed_m_s: Optional[float]
    e_dry: float
    delta_ss_m: float


class Event(Block):
    t: float
    event: str
    gap_m: float
    u_rel_m_s: float


class Solver(Block):
    """The integrator's settings and statistics."""
    integrator: str
    linear_solver: str
    rtol: float
    atol: float
    absolute_tolerances: List[float]
    state: List[str]
    state_size: int
    max_step_s: float
    t_final_s: float
    measure_interval_s: float
    measure_samples: int
    steps: int
    rhs_evals: int
    jac_evals: int
    lin_iters: int
    lin_conv_fails: int
    nonlin_iters: int
    nonlin_conv_fails: int
    error_test_fails: int
    prec_setups: int
    prec_solves: int
    reinits: int
    breakpoints: int
    root_events: int
    root_fn_evals: int
    order_caps: int  # restarts with CVODE's BDF order capped at 2 (a ringing order 3-5)


class FlowGrid(Block):
    cells_per_diameter: int
    h_m: float
    levels: int
    nr: int
    nz: int
    memory_MB: float


class FlowEstimate(Block):
    """The cost estimated before the run."""
    total_s: float
    start_up_s: float
    steps_to_t_end_s: float
    force_system_blocks_s: float
    fields_s: float
    memory_MB: float
    q_applications: float
    steps: float
    field_snapshots: float


class Flow(Block):
    """The flow kernel of a coupled run: its grid, cost and statistics."""
    start: str
    force_in_step: str
    grid: FlowGrid
    estimate: FlowEstimate
    steps: int
    dt_s: float
    dt_min_s: float
    dt_max_s: float
    step_changes: int
    cfl: float
    max_courant: float
    ms_per_step: float
    flow_time_s: float
    ode_time_s: float
    fields_time_s: float
    cpu_time_s: float
    flow_share: float
    ode_share: float
    start_up_steps: int
    start_up_time_s: float
    krylov_iterations: int
    krylov_iterations_per_step: float
    max_krylov_iterations: int
    q_applications: int
    start_up_q_applications: int
    preconditioner_blocks: int
    max_krylov_residual: float
    max_slip_m_s: float
    max_energy_ratio: float
    frame_travel_m: float
    min_gap_clamped_steps: int
    field_snapshots: int
    _blocks = {"grid": FlowGrid, "estimate": FlowEstimate}


class Summary(Block):
    """summary.json: what a run measured (units SI; docs/bounces.md for the measures of e)."""
    scene: str
    scene_file: str
    configuration: str
    fluid: Optional[Fluid]
    e: Optional[float]
    e_is: str
    e_missing: Optional[str]
    e_fit_raw: Optional[float]
    e_instant: Optional[float]
    e_instant_gap_m: float
    e_measures: Optional[Dict[str, Dict[str, Any]]]
    measures_disagree: Dict[str, float]
    energy_budget: Optional[Dict[str, Any]]
    bounces_mode: str
    bounces: List[Bounce]
    St: Optional[float]
    St_convention: str
    St_B_table_6_1: Optional[float]
    St_B_eq_6_2: Optional[float]
    St_L: Optional[float]
    St_initial: Optional[float]
    Re: Optional[float]
    separated: bool
    at_rest_since_s: Optional[float]
    t_end_too_short: bool
    final_phase: Optional[str]
    contacts: int
    velocities_m_s: Optional[Velocities]
    fit_window_s: float
    min_gap_m: Optional[float]
    max_contact_force_N: Optional[float]
    max_history_force_N: Optional[float]
    group_velocity_m_s: Optional[float]
    group_velocity_at_s: Optional[float]
    u1_final_m_s: Optional[float]
    u2_final_m_s: Optional[float]
    contact: Optional[Contact]
    effects: List[str]
    model: Dict[str, Any]
    solver: Solver
    events: List[Event]
    warnings: List[str]
    flow: Optional[Flow]
    wall_time_s: float
    setup_time_s: float
    _blocks = {"fluid": Fluid, "velocities_m_s": Velocities, "bounces": Bounce, "contact": Contact,
               "solver": Solver, "events": Event, "flow": Flow}
    _plain = frozenset({"e_measures", "measures_disagree", "energy_budget", "model", "run"})
