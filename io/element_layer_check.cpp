#include "io/element_layer_check.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <stdexcept>

#include "iga/problem.hpp"
#include "io/bloch_wave_text.hpp"

namespace isomuscle::io {

iga::LayerGeometry element_layer_at(const iga::Problem& problem, const SurfaceLocation& where) {
  if (where.side_direction < 0 || where.side_direction > 2)
    throw std::invalid_argument("the element layer check needs a side of a NURBS solid");
  if (problem.formulation() != iga::Formulation::mixed)
    throw std::invalid_argument("the element layer check is made for the mixed formulation");
  const iga::Space& space = problem.space();
  const geometry::NurbsVolume& volume = space.volume();
  const int d = where.side_direction, a = (d + 1) % 3, b = (d + 2) % 3;
  const iga::Element& element = space.element(where.element);
  const Eigen::Matrix3d& J = space.jacobian(where.element, where.point);
  const auto width = [&](int dir) {
    return element.box[static_cast<std::size_t>(dir)][1] -
           element.box[static_cast<std::size_t>(dir)][0];
  };
  iga::LayerGeometry layer;
  layer.degrees = {volume.degree(a), volume.degree(b), volume.degree(d)};
  // Into the body: against +dX/dxi_d at the side xi_d = max, along it at xi_d = min.
  layer.edges = {J.col(a) * width(a), J.col(b) * width(b),
                 (where.side_end == 1 ? -1.0 : 1.0) * J.col(d)};
  const std::vector<double> breaks = volume.knots(d).breakpoints();
  layer.depth_spans.clear();
  for (std::size_t k = 1; k < breaks.size(); ++k)
    layer.depth_spans.push_back(breaks[k] - breaks[k - 1]);
  if (where.side_end == 1)
    std::reverse(layer.depth_spans.begin(), layer.depth_spans.end());
  layer.pressure_degree = problem.options().pressure_degree;
  const std::array<int, 3>& points = space.points_per_direction();
  layer.quadrature_points = {points[static_cast<std::size_t>(a)],
                             points[static_cast<std::size_t>(b)],
                             points[static_cast<std::size_t>(d)]};
  return layer;
}

ElementLayerCheck assess_element_layer(const iga::Problem& problem, const SurfaceLocation& where) {
  const auto begin = std::chrono::steady_clock::now();
  ElementLayerCheck check;
  check.surface_position = where.surface_position;
  check.shear_modulus = problem.law().shear_modulus();
  check.layer = element_layer_at(problem, where);
  const iga::LayerGeometry& layer = check.layer;
  const iga::LayerState state = problem.committed_layer_state(where.element, where.point);
  check.lowest = iga::PeriodicLayer(layer, state).lowest();
  const iga::PeriodicLayer halved(iga::subdivided(layer, 2), state);
  check.lowest_halved = halved.lowest();
  check.same_wave.emplace_back(2, halved.lowest_at(check.lowest.angles / 2.0).eigenvalue);
  check.same_wave.emplace_back(4, iga::PeriodicLayer(iga::subdivided(layer, 4), state)
                                      .lowest_at(check.lowest.angles / 4.0)
                                      .eigenvalue);
  check.column = assess_element_column(problem, where);
  check.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  return check;
}

double element_layer_value(const iga::Problem& problem, const SurfaceLocation& where) {
  return lowest_eigenvalue_or_nan([&] {
    return iga::PeriodicLayer(element_layer_at(problem, where),
                              problem.committed_layer_state(where.element, where.point));
  });
}

std::string describe(const ElementLayerCheck& c) {
  const iga::LayerGeometry& l = c.layer;
  double depth = 0.0;
  for (double w : l.depth_spans)
    depth += w * l.edges[2].norm();
  char head[512];
  std::snprintf(head, sizeof head,
                "the run's element tiled along the free surface at (%.4g, %.4g, %.4g) m (spans of "
                "%.3g x %.3g mm, %zu spans in %.3g mm of depth, pressure degree %d) and deformed "
                "to the state there has its lowest Bloch eigenvalue %s Pa/m^2 (%s mu/mm^2) for a "
                "wave of %s x %s spans (%s with the elements halved); the same wave on elements "
                "cut 2 and 4 times has %s and %s Pa/m^2",
                c.surface_position.x(), c.surface_position.y(), c.surface_position.z(),
                1e3 * l.edges[0].norm(), 1e3 * l.edges[1].norm(), l.depth_spans.size(), 1e3 * depth,
                l.pressure_degree, signed_number(c.lowest.eigenvalue).c_str(),
                signed_number(c.lowest.eigenvalue * 1e-6 / c.shear_modulus).c_str(),
                spans_per_wave(c.lowest.angles[0]).c_str(),
                spans_per_wave(c.lowest.angles[1]).c_str(),
                signed_number(c.lowest_halved.eigenvalue).c_str(),
                signed_number(c.same_wave.at(0).second).c_str(),
                signed_number(c.same_wave.at(1).second).c_str());
  std::string text = head;
  if (c.lowest.eigenvalue > 0.0)
    text +=
        ": the element is stable at this state, so the instability needs the body itself (its "
        "geometry, the gradients of its state), not this local state alone";
  else if (c.same_wave.back().second > 0.0)
    text +=
        ": the element is unstable where finer elements are not, so the instability belongs "
        "to the discretisation (a spurious mode of the element whose wavelength and onset "
        "follow the mesh), not to the material or its surface";
  else
    text +=
        ": the same wave stays unstable on finer elements, an instability of the continuum at "
        "this state";
  return text + "; " + describe(c.column, c.shear_modulus);
}

}  // namespace isomuscle::io
