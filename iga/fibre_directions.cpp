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

// Unit direction of polyline segment [P_i, P_i+1].
Eigen::Vector3d unit_direction(const std::vector<Eigen::Vector3d>& p, std::size_t i) {
  return (p[i + 1] - p[i]).normalized();
}

// Normal of the miter plane at interior joint P_i: the mean of the unit directions of the two
// segments that meet there, so the plane makes equal angles with both (the bisecting plane).
Eigen::Vector3d miter_normal(const std::vector<Eigen::Vector3d>& p, std::size_t i) {
  return unit_direction(p, i - 1) + unit_direction(p, i);
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

FibreSpec FibreSpec::segments_cut_at(std::vector<Eigen::Vector3d> points, int direction,
                                     std::vector<double> cuts) {
  FibreSpec s;
  s.mode = Mode::polyline;
  s.polyline = std::move(points);
  s.cut_direction = direction;
  s.cuts = std::move(cuts);
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
      for (std::size_t i = 1; i + 1 < polyline.size(); ++i) {
        if (!(miter_normal(polyline, i).norm() > 1e-12)) {
          throw std::invalid_argument("fibre polyline turns back on itself at point " +
                                      std::to_string(i) + ": the joint has no bisecting plane");
        }
      }
      if (cut_direction >= 0) {
        if (cut_direction > 2) {
          throw std::invalid_argument("fibre polyline cut direction " +
                                      std::to_string(cut_direction) +
                                      " invalid (valid: 0 = u, 1 = v, 2 = w, -1 = miter planes)");
        }
        if (cuts.size() + 2 != polyline.size()) {
          throw std::invalid_argument("fibre polyline of " + std::to_string(polyline.size() - 1) +
                                      " segments needs " + std::to_string(polyline.size() - 2) +
                                      " parametric cuts, got " + std::to_string(cuts.size()));
        }
        for (std::size_t i = 0; i < cuts.size(); ++i) {
          if (!std::isfinite(cuts[i]) || (i > 0 && !(cuts[i] > cuts[i - 1]))) {
            throw std::invalid_argument("fibre polyline cuts must be finite and increasing");
          }
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
  if (spec.mode == FibreSpec::Mode::polyline && spec.cut_direction >= 0) {
    throw std::invalid_argument("fibre polyline with parametric cuts needs the point's xi");
  }
  return fibre_direction(spec, jac, X, Eigen::Vector3d::Zero());
}

Eigen::Vector3d fibre_direction(const FibreSpec& spec, const Eigen::Matrix3d& jac,
                                const Eigen::Vector3d& X, const Eigen::Vector3d& xi) {
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
      std::size_t segment = 0;
      if (spec.cut_direction >= 0) {
        // Parametric cuts: the number of cuts at or below xi_d.
        const auto above =
            std::upper_bound(spec.cuts.begin(), spec.cuts.end(), xi[spec.cut_direction]);
        segment = static_cast<std::size_t>(above - spec.cuts.begin());
      } else {
        // Walk the joints in order: X is past joint i when it lies on the far side of the miter
        // plane there. Nearest-segment distance would tie exactly on the convex side of a joint,
        // where both distances are |X - P_i|, and leave that region to round-off.
        for (std::size_t i = 1; i + 1 < spec.polyline.size(); ++i) {
          if ((X - spec.polyline[i]).dot(miter_normal(spec.polyline, i)) <= 0.0)
            break;
          segment = i;
        }
      }
      return unit_direction(spec.polyline, segment);
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
          fibre_direction(spec, space.jacobian(e, q), space.position(e, q), space.parametric(e, q));
    }
  }
  return out;
}

}  // namespace isomuscle::iga
