// `isomuscle geometry ...`: what an IGES file holds, and the shrink solid built from it.
//   isomuscle geometry info FILE.igs [--json]
//   isomuscle geometry solid FILE.igs [--surface N] --centreline u|v [--json] [--vtk OUT.vtk]
//                            [--vtk-divisions N]
//   isomuscle geometry examples --out DIR [--unit mm|m]
// --centreline names the surface's parametric direction that RUNS ALONG the centreline; the other
// one must close around it (thesis 5.13–5.15, SPEC §1). Lengths are reported in metres.
#include <Eigen/Core>
#include <Eigen/LU>
#include <array>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/command_registry.hpp"
#include "geometry/coincident_points.hpp"
#include "geometry/fibre_field.hpp"
#include "geometry/iges.hpp"
#include "geometry/parametric_skew.hpp"
#include "geometry/shapes.hpp"
#include "geometry/shrink.hpp"
#include "geometry/volume_measures.hpp"

namespace isomuscle::app {

namespace {

namespace geo = isomuscle::geometry;
using nlohmann::json;

constexpr int kJacobianSamplesPerSpan = 4;

struct InfoArgs {
  std::string file;
  bool json = false;
};

struct SolidArgs {
  std::string file;
  int surface = 0;
  std::string centreline;
  bool json = false;
  std::string vtk;
  int vtk_divisions = 4;
};

struct ExamplesArgs {
  std::string out;
  std::string unit = "mm";
};

const char* yes_no(bool b) {
  return b ? "yes" : "no";
}

json vector_json(const Eigen::Vector3d& x) {
  return json::array({x.x(), x.y(), x.z()});
}

json surface_json(const geo::IgesSurface& s, int index) {
  const geo::NurbsSurface& n = s.surface;
  Eigen::Vector3d lo = n.points().front(), hi = n.points().front();
  for (const Eigen::Vector3d& x : n.points()) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  const geo::SeamGap gap_u = geo::seam_gap(n, 0);
  const geo::SeamGap gap_v = geo::seam_gap(n, 1);
  const auto closed = [](const geo::SeamGap& g) {
    return g.relative <= geo::kDefaultClosureTolerance &&
           g.weight_ratio_spread <= geo::kDefaultClosureTolerance;
  };
  return {{"index", index},
          {"directory_entry", s.directory_entry},
          {"form", s.form},
          {"parent_type", s.parent_type},
          {"parent_directory_entry", s.parent_directory_entry},
          {"degrees", {n.knots_u().degree(), n.knots_v().degree()}},
          {"control_points", {n.count_u(), n.count_v()}},
          {"rational", n.is_rational()},
          {"closed_flag", {{"u", s.closed_flag[0]}, {"v", s.closed_flag[1]}}},
          {"periodic_flag", {{"u", s.periodic_flag[0]}, {"v", s.periodic_flag[1]}}},
          {"clamped_in_file", {{"u", s.clamped_in_file[0]}, {"v", s.clamped_in_file[1]}}},
          {"closed_control_net", {{"u", closed(gap_u)}, {"v", closed(gap_v)}}},
          {"seam_gap_relative", {{"u", gap_u.relative}, {"v", gap_v.relative}}},
          {"knot_domain",
           {{"u", {n.knots_u().domain_begin(), n.knots_u().domain_end()}},
            {"v", {n.knots_v().domain_begin(), n.knots_v().domain_end()}}}},
          {"parameter_range",
           {{"u", {s.parameter_range[0][0], s.parameter_range[0][1]}},
            {"v", {s.parameter_range[1][0], s.parameter_range[1][1]}}}},
          {"bounding_box_m", {{"min", vector_json(lo)}, {"max", vector_json(hi)}}}};
}

std::string parent_text(const geo::IgesSurface& s) {
  switch (s.parent_type) {
    case 0:
      return "stands alone";
    case 144:
      return "basis of trimmed surface (144) at DE " + std::to_string(s.parent_directory_entry);
    case 143:
      return "basis of bounded surface (143) at DE " + std::to_string(s.parent_directory_entry);
    default:
      return "surface of entity " + std::to_string(s.parent_type) + " at DE " +
             std::to_string(s.parent_directory_entry);
  }
}

void run_info(const InfoArgs& args) {
  const std::vector<geo::IgesSurface> surfaces = geo::read_iges_surfaces(args.file);
  json out = {{"file", args.file},
              {"unit", surfaces.front().file_unit},
              {"metres_per_unit", surfaces.front().metres_per_file_unit},
              {"surfaces", json::array()}};
  for (std::size_t k = 0; k < surfaces.size(); ++k) {
    out["surfaces"].push_back(surface_json(surfaces[k], static_cast<int>(k)));
  }
  if (args.json) {
    std::cout << out.dump(2) << "\n";
    return;
  }
  std::cout << args.file << ": " << surfaces.size()
            << " B-spline surface(s) (entity 128), file unit " << surfaces.front().file_unit << " ("
            << surfaces.front().metres_per_file_unit << " m)\n";
  for (std::size_t k = 0; k < surfaces.size(); ++k) {
    const json& s = out["surfaces"][k];
    const auto yn = [&](const char* key, const char* dir) {
      return yes_no(s[key][dir].get<bool>());
    };
    std::cout << "surface " << k << ": entity 128 form " << s["form"] << " at DE "
              << s["directory_entry"] << ", " << parent_text(surfaces[k]) << "\n"
              << "  degrees " << s["degrees"][0] << " x " << s["degrees"][1] << ", control points "
              << s["control_points"][0] << " x " << s["control_points"][1] << ", "
              << (s["rational"].get<bool>() ? "rational" : "polynomial") << "\n"
              << "  closed u: file flag " << yn("closed_flag", "u") << ", control net "
              << yn("closed_control_net", "u") << " (seam gap "
              << s["seam_gap_relative"]["u"].get<double>() << " of the diagonal)"
              << "; closed v: file flag " << yn("closed_flag", "v") << ", control net "
              << yn("closed_control_net", "v") << " (seam gap "
              << s["seam_gap_relative"]["v"].get<double>() << ")\n"
              << "  periodic flag u " << yn("periodic_flag", "u") << ", v "
              << yn("periodic_flag", "v") << "; knot vector clamped in the file: u "
              << yn("clamped_in_file", "u") << ", v " << yn("clamped_in_file", "v") << "\n"
              << "  bounding box [m]: min " << s["bounding_box_m"]["min"] << ", max "
              << s["bounding_box_m"]["max"] << "\n";
  }
}

// Legacy VTK unstructured grid: hexahedra of a parametric grid with `divisions` cells per knot
// span and direction; point data: the fibre direction along the centreline (thesis 5.29) and
// det J. Cells at w = 1 are degenerate (collapsed axis), as the solid is.
void write_vtk(const std::string& path, const geo::NurbsVolume& volume, int divisions,
               const std::string& title) {
  std::array<std::vector<double>, 3> grid;
  for (int d = 0; d < 3; ++d) {
    const std::vector<double> breaks = volume.knots(d).breakpoints();
    for (std::size_t e = 0; e + 1 < breaks.size(); ++e) {
      for (int k = 0; k < divisions; ++k) {
        grid[d].push_back(breaks[e] + (breaks[e + 1] - breaks[e]) * k / divisions);
      }
    }
    grid[d].push_back(breaks.back());
  }
  const int n0 = static_cast<int>(grid[0].size());
  const int n1 = static_cast<int>(grid[1].size());
  const int n2 = static_cast<int>(grid[2].size());
  const int num_points = n0 * n1 * n2;
  const int num_cells = (n0 - 1) * (n1 - 1) * (n2 - 1);
  std::vector<Eigen::Vector3d> points, fibres;
  std::vector<double> jacobians;
  Eigen::Vector3d x;
  Eigen::Matrix3d jacobian;
  for (int k = 0; k < n2; ++k) {
    for (int j = 0; j < n1; ++j) {
      for (int i = 0; i < n0; ++i) {
        const Eigen::Vector3d xi(grid[0][i], grid[1][j], grid[2][k]);
        volume.evaluate_with_jacobian(xi, x, jacobian);
        points.push_back(x);
        jacobians.push_back(jacobian.determinant());
        fibres.push_back(geo::fibre_direction(volume, xi, geo::kAlongCentreline));
      }
    }
  }
  std::ofstream out(path);
  if (!out)
    throw std::runtime_error("cannot open '" + path + "' for writing");
  out << std::setprecision(12);
  out << "# vtk DataFile Version 3.0\n" << title << "\nASCII\nDATASET UNSTRUCTURED_GRID\n";
  out << "POINTS " << num_points << " double\n";
  for (const Eigen::Vector3d& p : points)
    out << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  out << "CELLS " << num_cells << ' ' << 9 * num_cells << '\n';
  const auto id = [&](int i, int j, int k) { return i + n0 * (j + n1 * k); };
  for (int k = 0; k + 1 < n2; ++k) {
    for (int j = 0; j + 1 < n1; ++j) {
      for (int i = 0; i + 1 < n0; ++i) {
        out << "8 " << id(i, j, k) << ' ' << id(i + 1, j, k) << ' ' << id(i + 1, j + 1, k) << ' '
            << id(i, j + 1, k) << ' ' << id(i, j, k + 1) << ' ' << id(i + 1, j, k + 1) << ' '
            << id(i + 1, j + 1, k + 1) << ' ' << id(i, j + 1, k + 1) << '\n';
      }
    }
  }
  out << "CELL_TYPES " << num_cells << '\n';
  for (int c = 0; c < num_cells; ++c)
    out << "12\n";
  out << "POINT_DATA " << num_points << "\nVECTORS fibre double\n";
  for (const Eigen::Vector3d& a : fibres)
    out << a.x() << ' ' << a.y() << ' ' << a.z() << '\n';
  out << "SCALARS jacobian double 1\nLOOKUP_TABLE default\n";
  for (const double j : jacobians)
    out << j << '\n';
  out.close();
  if (!out)
    throw std::runtime_error("error while writing '" + path + "'");
}

void run_solid(const SolidArgs& args) {
  const std::vector<geo::IgesSurface> surfaces = geo::read_iges_surfaces(args.file);
  const int count = static_cast<int>(surfaces.size());
  if (args.surface < 0 || args.surface >= count) {
    throw std::invalid_argument("--surface " + std::to_string(args.surface) + ": '" + args.file +
                                "' holds " + std::to_string(count) +
                                " B-spline surface(s), numbered 0.." + std::to_string(count - 1) +
                                " (see `isomuscle geometry info`)");
  }
  if (args.vtk_divisions < 1 || args.vtk_divisions > 64) {
    throw std::invalid_argument("--vtk-divisions " + std::to_string(args.vtk_divisions) +
                                ": use 1..64 cells per knot span");
  }
  const int along = geo::parse_surface_direction(args.centreline);
  const geo::IgesSurface& chosen = surfaces[static_cast<std::size_t>(args.surface)];
  const geo::NurbsVolume volume = geo::shrink_to_centreline(chosen.surface, 1 - along);
  const geo::VolumeEstimate estimate = geo::converged_solid_volume(volume);
  const geo::CoincidentPoints coincident = geo::find_coincident_points(volume);
  const geo::JacobianRange range = geo::jacobian_range(volume, kJacobianSamplesPerSpan);
  const geo::ParametricSkew skew = geo::parametric_skew(volume, kJacobianSamplesPerSpan);
  json skew_shares = json::object();
  for (std::size_t k = 0; k < geo::kSkewThresholdsDeg.size(); ++k)
    skew_shares[std::to_string(static_cast<int>(geo::kSkewThresholdsDeg[k]))] =
        skew.volume_share_below[k];
  const std::string sampling =
      "det J at cell-centred " + std::to_string(kJacobianSamplesPerSpan) + "x" +
      std::to_string(kJacobianSamplesPerSpan) + "x" + std::to_string(kJacobianSamplesPerSpan) +
      " points of every knot span (none on a span boundary, so none on the collapsed axis w = 1)";
  json out = {{"file", args.file},
              {"surface", args.surface},
              {"directory_entry", chosen.directory_entry},
              {"centreline", args.centreline},
              {"closed_direction", along == 0 ? "v" : "u"},
              {"degrees", {volume.degree(0), volume.degree(1), volume.degree(2)}},
              {"control_point_counts", {volume.count(0), volume.count(1), volume.count(2)}},
              {"control_points", volume.num_control_points()},
              {"distinct_control_points", coincident.num_distinct},
              {"volume_m3", estimate.volume},
              {"volume_gauss_points_per_direction", estimate.points_per_direction},
              {"volume_relative_change_last_refinement", estimate.relative_change},
              {"min_jacobian", range.min},
              {"min_jacobian_at", vector_json(range.argmin)},
              {"max_jacobian", range.max},
              {"max_jacobian_at", vector_json(range.argmax)},
              {"jacobian_samples", range.samples},
              {"non_positive_jacobian_samples", range.non_positive},
              {"jacobian_sampling", sampling},
              {"min_parametric_angle_deg", skew.min_angle_deg},
              {"min_parametric_angle_at", vector_json(skew.argmin)},
              {"min_parametric_angle_between", skew.between},
              {"volume_share_parametric_angle_below_deg", skew_shares}};
  if (!args.vtk.empty()) {
    write_vtk(args.vtk, volume, args.vtk_divisions,
              "isomuscle shrink solid of " + args.file + " surface " +
                  std::to_string(args.surface) + ", fibres along the centreline");
    out["vtk"] = args.vtk;
  }
  if (args.json) {
    std::cout << out.dump(2) << "\n";
  } else {
    std::cout << std::setprecision(10) << "shrink solid of " << args.file << " surface "
              << args.surface << " (DE " << chosen.directory_entry << "), centreline along "
              << args.centreline << "\n"
              << "  degrees (around, along, towards the centreline) " << out["degrees"] << "\n"
              << "  control points " << out["control_point_counts"] << " = "
              << volume.num_control_points() << ", distinct " << coincident.num_distinct << "\n"
              << "  volume " << estimate.volume << " m^3 (" << estimate.points_per_direction
              << " Gauss points per direction, last change " << estimate.relative_change << ")\n"
              << "  det J in [" << range.min << ", " << range.max << "] m^3 (" << range.non_positive
              << " of " << range.samples << " samples <= 0; " << sampling << ")\n"
              << std::setprecision(3) << "  parametric directions meet at >= " << skew.min_angle_deg
              << " degrees (" << skew.between << ", at (u, v, w) = (" << skew.argmin.x() << ", "
              << skew.argmin.y() << ", " << skew.argmin.z()
              << ")); volume share below 15 / 30 / 45 degrees: " << 100 * skew.volume_share_below[0]
              << " / " << 100 * skew.volume_share_below[1] << " / "
              << 100 * skew.volume_share_below[2] << " % (every refinement keeps these angles)\n";
    if (!args.vtk.empty())
      std::cout << "  wrote " << args.vtk << "\n";
  }
  if (range.non_positive > 0) {
    throw std::runtime_error(
        std::to_string(range.non_positive) + " of " + std::to_string(range.samples) +
        " samples of det J are not positive (smallest " + std::to_string(range.min) +
        " at (u, v, w) = (" + std::to_string(range.argmin.x()) + ", " +
        std::to_string(range.argmin.y()) + ", " + std::to_string(range.argmin.z()) +
        ")): the solid folds over itself; is the centreline inside the "
        "surface everywhere (star-shaped sections)?");
  }
}

void run_examples(const ExamplesArgs& args) {
  const geo::IgesUnit unit = geo::parse_iges_unit(args.unit);
  std::filesystem::create_directories(args.out);
  for (const geo::ExampleShape& shape : geo::example_shapes()) {
    const std::filesystem::path path = std::filesystem::path(args.out) / (shape.name + ".igs");
    geo::write_iges(path, {shape.surface}, unit);
    std::cout << path.string() << ": " << shape.description;
    if (shape.exact_volume) {
      std::cout << std::setprecision(15) << "; shrink-solid volume " << *shape.exact_volume
                << " m^3";
    }
    std::cout << "\n";
  }
  // Cook's membrane is unit-free: written in metres whatever --unit says, so that the numbers of
  // the benchmark (48, 44, 60) are the scene's numbers.
  const std::filesystem::path cook = std::filesystem::path(args.out) / "cook.igs";
  geo::write_iges(cook, {geo::cook_membrane_surface()}, geo::IgesUnit::kMetre);
  std::cout << cook.string()
            << ": Cook's membrane, the tapered panel (0, 0), (48, 44), (48, 60), (0, 44) "
               "(unit-free benchmark, written as metres)\n";
}

// Runs a command body; errors become a message on stderr and exit code 1.
template <class Body>
void guarded(const char* command, Body body) {
  try {
    body();
    set_exit_code(0);
  } catch (const std::exception& e) {
    std::cerr << "isomuscle " << command << ": error: " << e.what() << "\n";
    set_exit_code(1);
  }
}

void install(CLI::App& app) {
  auto* geometry = app.add_subcommand(
      "geometry", "IGES surfaces and the NURBS solids shrunk from them (thesis 5.3)");
  geometry->require_subcommand(1);

  auto info_args = std::make_shared<InfoArgs>();
  auto* info = geometry->add_subcommand("info", "What B-spline surfaces an IGES file holds");
  info->add_option("file", info_args->file, "IGES file")->required();
  info->add_flag("--json", info_args->json, "Machine-readable output");
  info->callback([info_args] { guarded("geometry info", [&] { run_info(*info_args); }); });

  auto solid_args = std::make_shared<SolidArgs>();
  auto* solid = geometry->add_subcommand(
      "solid", "Shrink a closed surface onto its centreline (thesis 5.13-5.15) and measure it");
  solid->add_option("file", solid_args->file, "IGES file")->required();
  solid->add_option("--surface", solid_args->surface, "Which surface (0-based, see info)")
      ->capture_default_str();
  solid
      ->add_option("--centreline", solid_args->centreline,
                   "u | v: the parametric direction that runs ALONG the centreline; the other "
                   "one must be closed")
      ->required();
  solid->add_flag("--json", solid_args->json, "Machine-readable output");
  solid->add_option("--vtk", solid_args->vtk,
                    "Write a legacy VTK hexahedral tessellation with the fibre field");
  solid
      ->add_option("--vtk-divisions", solid_args->vtk_divisions,
                   "Cells per knot span and direction in the VTK file")
      ->capture_default_str();
  solid->callback([solid_args] { guarded("geometry solid", [&] { run_solid(*solid_args); }); });

  auto examples_args = std::make_shared<ExamplesArgs>();
  auto* examples = geometry->add_subcommand(
      "examples", "Write the example surfaces (cone, barrel, torus, half torus, DAO) as IGES");
  examples->add_option("--out", examples_args->out, "Output directory")->required();
  examples->add_option("--unit", examples_args->unit, "mm | m: length unit of the files")
      ->capture_default_str();
  examples->callback(
      [examples_args] { guarded("geometry examples", [&] { run_examples(*examples_args); }); });
}

const CommandRegistration registration{install};

}  // namespace

}  // namespace isomuscle::app
