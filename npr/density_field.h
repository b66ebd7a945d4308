// The metaball density field of Luft et al. Eq. 2 and 3: F(q) = sum_i D_i(q) - tau with
// D_i(q) = (1 - (|q - p_i| / rho)^2)^2 inside radius rho, 0 outside. Generators are bucketed
// in a uniform hash grid of cell size rho, so a query touches only the 27 cells around it
// and building costs time linear in the generators.
#pragma once

#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "core/scene/scene.h"
#include "npr/scalar_grid.h"

namespace sylva {

class DensityField {
 public:
  // rho: radius of influence, scene units, finite and > 0. tau: threshold, finite and >= 0.
  // Throws InputError("rho" / "tau", ...) otherwise. Generators must be finite.
  DensityField(std::vector<glm::vec3> generators, float rho, float tau);
  ~DensityField();
  DensityField(DensityField&&) noexcept;
  DensityField& operator=(DensityField&&) noexcept;

  // F(q) (Eq. 3). Exact: sums every generator within rho.
  float value(const glm::vec3& q) const;
  // F(q) and its analytic gradient: grad D_i = -4 (1 - s) (q - p_i) / rho^2, s = |q-p_i|^2/rho^2.
  float value_and_gradient(const glm::vec3& q, glm::vec3& gradient) const;
  // F at every node of `grid` (its dims/origin/spacing already set), written into
  // grid.values. Splats each generator into the nodes within rho (parallel over z slabs,
  // deterministic: the same bytes for any thread count).
  void fill_grid(ScalarGrid& grid) const;

  float rho() const { return m_rho; }
  float tau() const { return m_tau; }
  const std::vector<glm::vec3>& generators() const { return m_generators; }
  Bounds generator_bounds() const;

 private:
  struct Index;
  std::vector<glm::vec3> m_generators;
  float m_rho = 1.0f;
  float m_tau = 0.0f;
  std::unique_ptr<Index> m_index;
};

}  // namespace sylva
