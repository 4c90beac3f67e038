# SPDX-License-Identifier: BSD-3-Clause
# Types of the extension module imcol._imcol, for editors and type checkers (the package re-exports these names).
import os
from typing import Any, Callable, Dict, List, Optional, Sequence, Union

import numpy as np

from ._summary import Bounce, Contact, Event, Flow, Fluid, Solver, Summary, Velocities

# progress(done, total, eta_s): called on the calling thread while a long call runs (a run: simulated s of t_end;
# a study: runs finished of all); an exception raised in it stops the work and propagates.
Progress = Callable[[float, float, float], object]

__version__: str

class SolverError(RuntimeError):
    """The time integrator failed: what failed, when, and which state components were to blame."""
    integrator: Optional[str]
    flag: Optional[int]
    flag_name: Optional[str]
    time: Optional[float]
    state: Optional[Dict[str, float]]
    local_errors: Optional[Dict[str, float]]

_Value = Union[str, bool, int, float, np.generic, np.ndarray, Sequence[Union[str, bool, int, float, np.generic]]]

# What every call's `scene` takes: an imcol.Scene, a shipped scene's name ("default", "coupled/gg3462") or the path of
# a scene file.
_SceneArg = Union["Scene", str, "os.PathLike[str]"]

class Scene:
    """A scene: a TOML file or text, with keys set on it as the command line's --set does."""
    @staticmethod
    def load(name_or_path: _SceneArg) -> Scene: ...
    @staticmethod
    def from_toml(text: str) -> Scene: ...
    def set(self, key: str, value: _Value) -> Scene: ...
    @property
    def name(self) -> str: ...
    @property
    def path(self) -> str: ...
    @property
    def description(self) -> str: ...
    @property
    def toml(self) -> str: ...
    @property
    def overrides(self) -> List[str]: ...
    def __copy__(self) -> Scene: ...
    def __deepcopy__(self, memo: Dict[int, Any]) -> Scene: ...

class Result:
    """What a run measured; the summary's names are attributes with their types (None where absent)."""
    @property
    def e(self) -> Optional[float]: ...
    @property
    def St(self) -> Optional[float]: ...
    @property
    def measures(self) -> Dict[str, Optional[float]]: ...
    @property
    def warnings(self) -> List[str]: ...
    @property
    def stats(self) -> Dict[str, Union[int, str]]: ...
    @property
    def bounces(self) -> List[Bounce]: ...
    @property
    def columns(self) -> List[str]: ...
    @property
    def trajectory(self) -> Dict[str, np.ndarray]: ...
    @property
    def summary(self) -> Summary: ...
    def to_dict(self) -> Dict[str, Any]: ...
    def __dir__(self) -> List[str]: ...
    # The summary's other names (imcol.Summary):
    scene: str
    scene_file: str
    configuration: str
    fluid: Optional[Fluid]
    e_is: str
    e_missing: Optional[str]
    e_fit_raw: Optional[float]
    e_instant: Optional[float]
    e_instant_gap_m: float
    e_measures: Optional[Dict[str, Dict[str, Any]]]
    measures_disagree: Dict[str, float]
    energy_budget: Optional[Dict[str, Any]]
    bounces_mode: str
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
    flow: Optional[Flow]
    wall_time_s: float
    setup_time_s: float

def run(scene: _SceneArg, rtol: Optional[float] = None, atol: Optional[float] = None, integrator: Optional[str] = None,
        record: str = "full", progress: Optional[Progress] = None) -> Result: ...

class SweepResult:
    """A sweep's points: sweep.csv's columns as NumPy arrays (every column is also an attribute)."""
    vary: str
    column: str
    table: Dict[str, np.ndarray]
    @property
    def values(self) -> np.ndarray: ...
    @property
    def St(self) -> np.ndarray: ...
    @property
    def e(self) -> np.ndarray: ...
    @property
    def status(self) -> np.ndarray: ...
    @property
    def messages(self) -> np.ndarray: ...
    @property
    def columns(self) -> List[str]: ...
    def to_dict(self) -> Dict[str, np.ndarray]: ...
    def __len__(self) -> int: ...
    def __getattr__(self, name: str) -> np.ndarray: ...
    def __dir__(self) -> List[str]: ...

def sweep(scene: _SceneArg, vary: str = "velocity", *, values: Sequence[float], jobs: int = 0,
          rtol: Optional[float] = None, atol: Optional[float] = None, integrator: Optional[str] = None,
          progress: Optional[Progress] = None) -> SweepResult: ...

class WorkPrecisionResult:
    """A work-precision ladder: work_precision.csv's columns as NumPy arrays (every column is also an attribute)."""
    table: Dict[str, np.ndarray]
    reference: Dict[str, Any]
    observed_order: Dict[str, Dict[str, Any]]
    cheapest: Dict[float, Optional[Dict[str, Any]]]
    @property
    def scene(self) -> str: ...
    @property
    def metric(self) -> str: ...
    @property
    def skipped(self) -> List[str]: ...
    @property
    def columns(self) -> List[str]: ...
    def to_dict(self) -> Dict[str, np.ndarray]: ...
    def __len__(self) -> int: ...
    def __getattr__(self, name: str) -> np.ndarray: ...
    def __dir__(self) -> List[str]: ...

class StudyTable:
    """A study's rows: the command's CSV columns as NumPy arrays (every column is also an attribute), and `info`."""
    kind: str
    table: Dict[str, np.ndarray]
    info: Dict[str, Any]
    @property
    def columns(self) -> List[str]: ...
    def to_dict(self) -> Dict[str, np.ndarray]: ...
    def __len__(self) -> int: ...
    def __getattr__(self, name: str) -> np.ndarray: ...
    def __dir__(self) -> List[str]: ...

def work_precision(scene: _SceneArg, rtols: Optional[Sequence[float]] = None, integrators: Optional[Sequence[str]] = None,
                   evaluators: Optional[Sequence[str]] = None, repeat: int = 3, direct_steps: Optional[Sequence[float]] = None,
                   direct_rtol: float = 1e-10, ref_rtol: float = 1e-13, ref_history_tolerance: float = 1e-11,
                   add_history: bool = False, jobs: int = 1, progress: Optional[Progress] = None) -> WorkPrecisionResult: ...

class ValidateResult:
    """The seed's Table 6.1 against imcol: validate_seed.csv's columns as NumPy arrays (every column is also an attribute)."""
    table: Dict[str, np.ndarray]
    agreement: List[Dict[str, Any]]
    @property
    def flow(self) -> bool: ...
    @property
    def tolerance(self) -> float: ...
    @property
    def columns(self) -> List[str]: ...
    def to_dict(self) -> Dict[str, np.ndarray]: ...
    def __len__(self) -> int: ...
    def __getattr__(self, name: str) -> np.ndarray: ...
    def __dir__(self) -> List[str]: ...

def validate_seed(models: Optional[Sequence[str]] = None, flow: bool = False, tolerance: float = 0.05, jobs: int = 0,
                  rtol: Optional[float] = None, atol: Optional[float] = None, integrator: Optional[str] = None,
                  progress: Optional[Progress] = None) -> ValidateResult: ...

def laws(scene: _SceneArg, laws: Optional[Sequence[str]] = None, vary: Optional[str] = None,
         values: Optional[Sequence[float]] = None, rtol: Optional[float] = None, atol: Optional[float] = None,
         integrator: Optional[str] = None, progress: Optional[Progress] = None) -> StudyTable: ...

def history_compare(scene: _SceneArg, kernels: Optional[Sequence[str]] = None, evaluators: Optional[Sequence[str]] = None,
                    vary: Optional[str] = None, values: Optional[Sequence[float]] = None, jobs: int = 0,
                    rtol: Optional[float] = None, atol: Optional[float] = None, integrator: Optional[str] = None,
                    progress: Optional[Progress] = None) -> StudyTable: ...

# info: dem.json's keys: St_convention, St_column, e_dry_scene, points, St_no_rebound_max, fits, best, exp, fit_error,
# liggghts (CriticalStokes, MaximumRestitution fitted through the replay of LIGGGHTS's hooke viscous rule; docs/dem.md).
def dem_fit(sweep: SweepResult) -> StudyTable: ...

class CalibrationResult:
    """A calibration's outcome, as calibration.json and calibration.csv of `imcol calibrate` hold it."""
    kind: str
    keys: List[str]
    values: Dict[str, float]
    start: Dict[str, float]
    intervals: Dict[str, Any]
    ok: bool
    objective: Optional[float]
    rms: Optional[float]
    tau_s: Optional[float]
    evaluations: Dict[str, np.ndarray]
    count: int
    failed: int
    profiles: Dict[str, Dict[str, Any]]
    factor_rule: Dict[str, Any]
    validation: Optional[Dict[str, Any]]
    stage_wall_s: Dict[str, float]
    wall_time_s: float
    jobs: int
    cancelled: bool
    def to_dict(self) -> Dict[str, Any]: ...

def calibrate(scene: _SceneArg, data: Any, fit: Union[str, Sequence[str], Dict[str, Sequence[Any]]], *,
              window: Union[None, str, Sequence[float]] = None, offset_max: Optional[float] = None,
              scan: Optional[int] = None, starts: int = 2, max_evals: int = 40, profile_points: int = 15,
              factor: Optional[float] = None, confidence: Optional[float] = None, refine: int = 16,
              refine_to: float = 0.015625, validate: Any = None, jobs: int = 0,
              progress: Optional[Callable[[int, int, float], Any]] = None) -> CalibrationResult: ...

def history_kernels() -> List[str]: ...
def integrators() -> List[str]: ...
def contact_laws() -> List[str]: ...
def lubrication_models() -> List[str]: ...
def drag_laws() -> List[str]: ...
def e_measures() -> List[str]: ...
def effects() -> List[str]: ...
def sweep_quantities() -> List[str]: ...
def scenes(pattern: str = "") -> List[str]: ...
def choices() -> Dict[str, List[str]]: ...
def data_dir() -> str: ...
def _set_data_dir(dir: str) -> None: ...
