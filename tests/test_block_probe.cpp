// SPDX-License-Identifier: BSD-3-Clause
// Probed preconditioner blocks (flow/solver.hpp, Settings::block_probe_stride): a sphere's later blocks of Q are the
// first block of its radius plus the change of Q probed at every stride-th ring point.
#include <gtest/gtest.h>

#include <cmath>

#include "flow/solver.hpp"
#include "flow_settings.hpp"

namespace {

imcol::flow::Settings probe_test_settings() {
  // D = 1, Re = 1, fluid at rest; finest level r < 1.5 D, −0.5 D < z < 4.5 D at 8 cells/D (13 ring points a sphere)
  imcol::flow::Settings s = imcol::flow::test_setup::stream_settings(1.0, 8, 2, 1.5, -0.5, 4.5, 0.01, 0.5);
  s.u_inf = 0.0;
  s.krylov_tol = 1e-10;
  s.preconditioner_bins = 4;
  return s;
}

double relative(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) { return (a - b).norm() / b.norm(); }

}  // namespace

TEST(BlockProbe, ExactWhenTheStrideCoversTheSphere) {
  // One probe per component: each column is Q's own, whatever the base.
  const auto st = probe_test_settings();
  imcol::flow::Solver s(st, {{0.5, 1.0 + 0.3 * st.h, 0.0}});
  const Eigen::MatrixXd Q = s.force_matrix();
  const Eigen::Index n = Q.rows();
  ASSERT_EQ(n, 26);
  const long before = s.q_applications();
  for (int stride : {13, 40}) {
    const Eigen::MatrixXd from_zero = s.corrected_block_of_Q(0, Eigen::MatrixXd::Zero(n, n), stride);
    EXPECT_LT(relative(from_zero, Q), 1e-13) << "stride " << stride;
    const Eigen::MatrixXd from_noise = s.corrected_block_of_Q(0, Eigen::MatrixXd::Random(n, n) * Q.norm(), stride);
    EXPECT_LT(relative(from_noise, Q), 1e-12) << "stride " << stride;
  }
  EXPECT_EQ(s.q_applications() - before, 4 * 2 * 13);  // 2 × min(stride, points) applications each
  EXPECT_THROW(s.corrected_block_of_Q(0, Q, 0), std::invalid_argument);
  EXPECT_THROW(s.corrected_block_of_Q(1, Q, 4), std::invalid_argument);
}

TEST(BlockProbe, CorrectsTheBlockOfAnotherOffset) {
  // The same sphere 0.37 cell further on: its block differs most near the diagonal, where the probe recovers it
  // (13 ring points: stride 4 and 8 are true probes, 12 all but one).
  const auto st = probe_test_settings();
  imcol::flow::Solver a(st, {{0.5, 1.0, 0.0}});
  imcol::flow::Solver b(st, {{0.5, 1.0 + 0.37 * st.h, 0.0}});
  const Eigen::MatrixXd Qa = a.force_matrix(), Qb = b.force_matrix();
  const double base_error = relative(Qa, Qb);
  EXPECT_GT(base_error, 1e-2);  // the offset matters
  // Its error falls with the stride (≈ stride⁻³, the change's decay along the ring): 0.37, 0.038, 0.009 of the base's.
  double last = base_error;
  for (int stride : {4, 8, 12}) {
    const long before = b.q_applications();
    const double error = relative(b.corrected_block_of_Q(0, Qa, stride), Qb);
    EXPECT_EQ(b.q_applications() - before, 2 * stride);
    EXPECT_LT(error, 0.5 * last) << "stride " << stride;
    last = error;
  }
  EXPECT_LT(last, 0.02 * base_error);
}

TEST(BlockProbe, SameForcesFromFewerForceSolves) {
  // Two spheres approaching across several cells: GMRES converges to the same forces with probed blocks, and the run
  // applies Q fewer times in all (blocks and iterations) than with every block built column by column (483 against
  // 532 at stride 8).
  auto run = [](int stride) {
    auto st = probe_test_settings();
    st.block_probe_stride = stride;
    st.krylov_tol = 1e-11;
    // Both runs start GMRES from the last two steps' forces, so that only the blocks differ. From the same offset
    // each run starts from its own earlier solves, and their forces differ by up to 2e-8 at this tolerance, the
    // solve's floor here (1e-12 does not converge: 5.7e-12 after 1000 iterations).
    st.warm_start_by_offset = false;
    std::vector<imcol::flow::SphereState> sp{{0.5, 1.0, 0.0}, {0.5, 2.6, 0.0}};
    imcol::flow::Solver s(st, sp);
    std::vector<double> forces;
    for (int k = 1; k <= 12; ++k) {
      const double dz = 0.3 * st.h;  // each sphere 0.3 cell a step: every bin is visited
      sp[0] = {0.5, sp[0].z + dz, dz / st.dt};
      sp[1] = {0.5, sp[1].z - dz, -dz / st.dt};
      const auto info = s.step(sp);
      forces.insert(forces.end(), info.force.begin(), info.force.end());
    }
    return std::make_tuple(forces, s.q_applications(), s.preconditioner_blocks_built());
  };
  const auto [f_full, q_full, blocks_full] = run(0);
  const auto [f_probe, q_probe, blocks_probe] = run(8);
  EXPECT_EQ(blocks_probe, blocks_full);
  EXPECT_GE(blocks_full, 8);  // 2 spheres × 4 bins
  EXPECT_LT(q_probe, q_full);
  ASSERT_EQ(f_probe.size(), f_full.size());
  for (std::size_t k = 0; k < f_full.size(); ++k) EXPECT_NEAR(f_probe[k], f_full[k], 1e-8 * std::abs(f_full[k])) << k;
}
