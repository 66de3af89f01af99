#include "iga/fibre_directions.hpp"

#include "geometry/fibre_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace isomuscle::iga {

namespace {

bool usable(const Eigen::Vector3d& v) {
  return v.allFinite() && v.norm() > 0.0;
}

// Distance from X to the closed segment [a, b].
double segment_distance(const Eigen::Vector3d& X, const Eigen::Vector3d& a,
                        const Eigen::Vector3d& b) {
  const Eigen::Vector3d d = b - a;
  const double t = std::clamp((X - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (X - (a + t * d)).norm();
}

}  // namespace

FibreSpec FibreSpec::isocurve(int direction) {
  FibreSpec s;
  s.mode = Mode::isocurve;
  s.direction = direction;
  s.validate();
  return s;
}

FibreSpec FibreSpec::constant(const Eigen::Vector3d& v) {
  FibreSpec s;
  s.mode = Mode::constant;
  s.vector = v;
  s.validate();
  return s;
}

FibreSpec FibreSpec::segments(std::vector<Eigen::Vector3d> points) {
  FibreSpec s;
  s.mode = Mode::polyline;
  s.polyline = std::move(points);
  s.validate();
  return s;
}

FibreSpec FibreSpec::origin_to_insertion(const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
  FibreSpec s;
  s.mode = Mode::origin_insertion;
  s.origin = p;
  s.insertion = q;
  s.validate();
  return s;
}

void FibreSpec::validate() const {
  switch (mode) {
    case Mode::isocurve:
      if (direction < 0 || direction > 2) {
        throw std::invalid_argument("fibre isocurve direction " + std::to_string(direction) +
                                    " invalid (valid: 0 = u, 1 = v, 2 = w)");
      }
      break;
    case Mode::constant:
      if (!usable(vector)) {
        throw std::invalid_argument("fibre constant vector must be finite and non-zero");
      }
      break;
    case Mode::polyline:
      if (polyline.size() < 2) {
        throw std::invalid_argument("fibre polyline needs at least 2 points (1 segment), got " +
                                    std::to_string(polyline.size()));
      }
      for (std::size_t i = 0; i + 1 < polyline.size(); ++i) {
        if (!polyline[i].allFinite() || !polyline[i + 1].allFinite() ||
            !((polyline[i + 1] - polyline[i]).norm() > 0.0)) {
          throw std::invalid_argument("fibre polyline segment " + std::to_string(i) +
                                      " has non-finite or coincident end points");
        }
      }
      break;
    case Mode::origin_insertion:
      if (!origin.allFinite() || !insertion.allFinite() || !((insertion - origin).norm() > 0.0)) {
        throw std::invalid_argument(
            "fibre origin and insertion points must be finite and distinct");
      }
      break;
  }
}

const char* to_string(FibreSpec::Mode mode) {
  switch (mode) {
    case FibreSpec::Mode::isocurve:
      return "isocurve";
    case FibreSpec::Mode::constant:
      return "constant";
    case FibreSpec::Mode::polyline:
      return "polyline";
    case FibreSpec::Mode::origin_insertion:
      return "origin_insertion";
  }
  return "?";
}

// Thesis 5.27–5.29: A = dH/dxi_d / |dH/dxi_d| (isocurve); the other modes as in the header.
Eigen::Vector3d fibre_direction(const FibreSpec& spec, const Eigen::Matrix3d& jac,
                                const Eigen::Vector3d& X) {
  switch (spec.mode) {
    case FibreSpec::Mode::isocurve:
      try {
        return geometry::fibre_direction(jac, spec.direction);
      } catch (const std::domain_error& err) {
        std::ostringstream msg;
        msg << "fibre isocurve direction " << geometry::parametric_direction_name(spec.direction)
            << " at X = (" << X[0] << ", " << X[1] << ", " << X[2] << "): " << err.what()
            << "; choose another direction";
        throw std::invalid_argument(msg.str());
      }
    case FibreSpec::Mode::constant:
      return spec.vector.normalized();
    case FibreSpec::Mode::polyline: {
      std::size_t best = 0;
      double best_d = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i + 1 < spec.polyline.size(); ++i) {
        const double d = segment_distance(X, spec.polyline[i], spec.polyline[i + 1]);
        if (d < best_d) {
          best_d = d;
          best = i;
        }
      }
      return (spec.polyline[best + 1] - spec.polyline[best]).normalized();
    }
    case FibreSpec::Mode::origin_insertion:
      return (spec.insertion - spec.origin).normalized();
  }
  return Eigen::Vector3d::UnitZ();
}

std::vector<Eigen::Vector3d> fibre_directions(const Space& space, const FibreSpec& spec) {
  spec.validate();
  std::vector<Eigen::Vector3d> out(static_cast<std::size_t>(space.num_points()));
  const int nqp = space.points_per_element();
  for (int e = 0; e < space.num_elements(); ++e) {
    for (int q = 0; q < nqp; ++q) {
      out[static_cast<std::size_t>(e) * nqp + q] =
          fibre_direction(spec, space.jacobian(e, q), space.position(e, q));
    }
  }
  return out;
}

}  // namespace isomuscle::iga
