#include "io/element_column_check.hpp"

#include <cstdio>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "iga/problem.hpp"
#include "io/bloch_wave_text.hpp"

namespace isomuscle::io {

iga::PeriodicLayer element_column_at(const iga::Problem& problem, const SurfaceLocation& where,
                                     const iga::LayerState* homogeneous) {
  if (where.side_direction < 0 || where.side_direction > 2)
    throw std::invalid_argument("the element column check needs a side of a NURBS solid");
  const iga::Space& space = problem.space();
  const geometry::NurbsVolume& volume = space.volume();
  // The surface directions in the uniform layer's order (element_layer_at), then the depth.
  const int d = where.side_direction, a = (d + 1) % 3, b = (d + 2) % 3;
  const std::array<int, 3>& site = space.element(where.element).position;
  const int rows = volume.count(d);
  std::vector<iga::ColumnElement> column;
  Eigen::VectorXd lumped = Eigen::VectorXd::Zero(rows);
  for (int e = 0; e < space.num_elements(); ++e) {
    const std::array<int, 3>& position = space.element(e).position;
    if (position[static_cast<std::size_t>(a)] != site[static_cast<std::size_t>(a)] ||
        position[static_cast<std::size_t>(b)] != site[static_cast<std::size_t>(b)])
      continue;
    iga::ColumnElement element;
    for (int cp : space.control_points(e)) {
      const std::array<int, 3> index = {cp % volume.count(0),
                                        (cp / volume.count(0)) % volume.count(1),
                                        cp / (volume.count(0) * volume.count(1))};
      const int k = index[static_cast<std::size_t>(d)];
      element.row.push_back(where.side_end == 1 ? rows - 1 - k : k);
      element.offset.emplace_back(index[static_cast<std::size_t>(a)],
                                  index[static_cast<std::size_t>(b)]);
    }
    element.tangent = problem.committed_element_tangent(e, homogeneous);
    for (int q = 0; q < space.points_per_element(); ++q) {
      const auto values = space.values(e, q);
      for (std::size_t f = 0; f < values.size(); ++f)
        lumped[element.row[f]] += values[f] * space.dv(e, q);
    }
    column.push_back(std::move(element));
  }
  return iga::PeriodicLayer(std::move(column), std::move(lumped));
}

ElementColumnCheck assess_element_column(const iga::Problem& problem,
                                         const SurfaceLocation& where) {
  ElementColumnCheck check;
  const iga::LayerState state = problem.committed_layer_state(where.element, where.point);
  check.lowest = element_column_at(problem, where).lowest();
  check.homogeneous = element_column_at(problem, where, &state).lowest();
  const int d = where.side_direction;
  check.elements = problem.space().element_counts()[static_cast<std::size_t>(d)];
  return check;
}

double element_column_value(const iga::Problem& problem, const SurfaceLocation& where) {
  try {
    return element_column_at(problem, where).lowest().eigenvalue;
  } catch (const std::runtime_error&) {
    return std::numeric_limits<double>::quiet_NaN();
  }
}

std::string describe(const ElementColumnCheck& c, double shear_modulus) {
  char head[512];
  std::snprintf(head, sizeof head,
                "the body's own column of %d elements through the depth there, tiled along the "
                "surface, has its lowest Bloch eigenvalue %s Pa/m^2 (%s mu/mm^2) for a wave of %s "
                "x %s spans with each element at its own state, and %s Pa/m^2 (%s x %s spans) with "
                "all at the surface point's state",
                c.elements, signed_number(c.lowest.eigenvalue).c_str(),
                signed_number(c.lowest.eigenvalue * 1e-6 / shear_modulus).c_str(),
                spans_per_wave(c.lowest.angles[0]).c_str(),
                spans_per_wave(c.lowest.angles[1]).c_str(),
                signed_number(c.homogeneous.eigenvalue).c_str(),
                spans_per_wave(c.homogeneous.angles[0]).c_str(),
                spans_per_wave(c.homogeneous.angles[1]).c_str());
  const std::string text = head;
  if (c.lowest.eigenvalue > 0.0)
    return text +
           ": a wave of the column is stable with the depth's gradients in, so the instability "
           "needs variation along the surface too (a localised state, the body's shape in plan)";
  if (c.homogeneous.eigenvalue > 0.0)
    return text +
           ": the column is unstable only at its own states, so the variation of the state "
           "through the depth makes it";
  return text +
         ": the column is unstable at the surface point's state too, so the shapes of the body's "
         "elements through the depth make it";
}

}  // namespace isomuscle::io
