#include "model/evaluation.hpp"

namespace imcol::model {

std::array<double, 2> Evaluation::accelerations(const std::array<double, 2>& g, std::size_t n) const {
  if (n == 1) return {g[0] / m_eff[0], 0.0};
  const double det = m_eff[0] * m_eff[1] - m_couple * m_couple;
  return {(m_eff[1] * g[0] - m_couple * g[1]) / det, (m_eff[0] * g[1] - m_couple * g[0]) / det};
}

}  // namespace imcol::model
