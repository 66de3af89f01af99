#include "io/element_column_check.hpp"

#include <cstdio>
#include <stdexcept>
#include <utility>
#include <vector>

#include "iga/problem.hpp"
#include "io/bloch_wave_text.hpp"

namespace isomuscle::io {

namespace {

// The column's elements with their depth rows and surface offsets, and the lumped volumes of the
// rows: what does not depend on the state the elements are taken at.
struct ColumnLayout {
  std::vector<int> elements;
  std::vector<iga::ColumnElement> column;  // tangents not yet set
  Eigen::VectorXd lumped;
};

ColumnLayout column_layout(const iga::Problem& problem, const SurfaceLocation& where) {
  if (where.side_direction < 0 || where.side_direction > 2)
    throw std::invalid_argument("the element column check needs a side of a NURBS solid");
  const iga::Space& space = problem.space();
  const geometry::NurbsVolume& volume = space.volume();
  // The surface directions in the uniform layer's order (element_layer_at), then the depth.
  const int d = where.side_direction, a = (d + 1) % 3, b = (d + 2) % 3;
  const std::array<int, 3>& site = space.element(where.element).position;
  const int rows = volume.count(d);
  ColumnLayout layout;
  layout.lumped = Eigen::VectorXd::Zero(rows);
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
    for (int q = 0; q < space.points_per_element(); ++q) {
      const auto values = space.values(e, q);
      for (std::size_t f = 0; f < values.size(); ++f)
        layout.lumped[element.row[f]] += values[f] * space.dv(e, q);
    }
    layout.elements.push_back(e);
    layout.column.push_back(std::move(element));
  }
  return layout;
}

// The layout's elements with their tangents at their committed states, or all at homogeneous.
iga::PeriodicLayer column_at(const iga::Problem& problem, ColumnLayout layout,
                             const iga::LayerState* homogeneous) {
  for (std::size_t i = 0; i < layout.column.size(); ++i)
    layout.column[i].tangent = problem.committed_element_tangent(layout.elements[i], homogeneous);
  return iga::PeriodicLayer(std::move(layout.column), std::move(layout.lumped));
}

}  // namespace

iga::PeriodicLayer element_column_at(const iga::Problem& problem, const SurfaceLocation& where,
                                     const iga::LayerState* homogeneous) {
  return column_at(problem, column_layout(problem, where), homogeneous);
}

ElementColumnCheck assess_element_column(const iga::Problem& problem,
                                         const SurfaceLocation& where) {
  ElementColumnCheck check;
  const iga::LayerState state = problem.committed_layer_state(where.element, where.point);
  ColumnLayout layout = column_layout(problem, where);
  check.elements = static_cast<int>(layout.elements.size());
  check.lowest = column_at(problem, layout, nullptr).lowest();
  check.homogeneous = column_at(problem, std::move(layout), &state).lowest();
  return check;
}

double element_column_value(const iga::Problem& problem, const SurfaceLocation& where) {
  return lowest_eigenvalue_or_nan([&] { return element_column_at(problem, where); });
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
