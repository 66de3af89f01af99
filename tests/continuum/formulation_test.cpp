// continuum::Formulation names, the formulation chosen for a law, the fibre check and the point
// stress outputs shared by iga/ and tet/.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <memory>
#include <string>

#include "continuum/formulation.hpp"
#include "continuum/point_state.hpp"
#include "continuum/problem_setup.hpp"
#include "materials/material_factory.hpp"

namespace isomuscle::continuum {
namespace {

TEST(Formulation, NamesRoundTripAndUnknownNameListsTheChoices) {
  for (Formulation f : {Formulation::automatic, Formulation::displacement, Formulation::mixed}) {
    EXPECT_EQ(parse_formulation(to_string(f)), f);
  }
  try {
    parse_formulation("hybrid");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'hybrid'"), std::string::npos) << what;
    EXPECT_NE(what.find("automatic, displacement, mixed"), std::string::npos) << what;
  }
}

// A law without a volumetric split: a neo-Hookean solid seen only through evaluate().
class UnsplitLaw : public materials::MaterialLaw {
 public:
  UnsplitLaw() : inner_(materials::make_material("neo_hookean")) {}
  std::string name() const override { return "unsplit_test_law"; }
  materials::PointStatus evaluate(const materials::PointInput& in, materials::PointResult& out,
                                  bool tangent) const override {
    return inner_->evaluate(in, out, tangent);
  }
  double shear_modulus() const override { return inner_->shear_modulus(); }
  double bulk_modulus() const override { return inner_->bulk_modulus(); }

 private:
  std::unique_ptr<materials::MaterialLaw> inner_;
};

TEST(Formulation, AutomaticChoosesMixedForNearlyIncompressibleSplitLaws) {
  // neo-Hookean: mu = 2 C10 = 2e4 Pa; kappa/mu = 50 (soft in volume) or 5e3 (stiff).
  const auto soft = materials::make_material("neo_hookean", {{"C10", 1e4}, {"K", 1e6}});
  const auto stiff = materials::make_material("neo_hookean", {{"C10", 1e4}, {"K", 1e8}});
  const auto linear = std::make_unique<UnsplitLaw>();
  ASSERT_TRUE(soft->has_volumetric_split());
  ASSERT_FALSE(linear->has_volumetric_split());
  const double ratio = soft->bulk_modulus() / soft->shear_modulus();
  EXPECT_EQ(resolve_formulation(Formulation::automatic, *soft, 0.5 * ratio), Formulation::mixed);
  EXPECT_EQ(resolve_formulation(Formulation::automatic, *soft, 2.0 * ratio),
            Formulation::displacement);
  EXPECT_EQ(resolve_formulation(Formulation::automatic, *stiff, 2.0 * ratio), Formulation::mixed);
  EXPECT_EQ(resolve_formulation(Formulation::automatic, *soft, 0.0), Formulation::mixed);
  EXPECT_EQ(resolve_formulation(Formulation::automatic, *linear, 0.0), Formulation::displacement);
  EXPECT_EQ(resolve_formulation(Formulation::displacement, *stiff, 1.0), Formulation::displacement);
  EXPECT_EQ(resolve_formulation(Formulation::mixed, *soft, 1e9), Formulation::mixed);
  try {
    resolve_formulation(Formulation::mixed, *linear, 0.0);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(linear->name()), std::string::npos) << what;
    EXPECT_NE(what.find("'displacement' or 'automatic'"), std::string::npos) << what;
  }
}

TEST(Formulation, FibreCheckNamesTheOwnerAndTheBadDirection) {
  std::vector<Eigen::Vector3d> fibres(3, Eigen::Vector3d::UnitX());
  EXPECT_NO_THROW(check_unit_fibres(fibres, 3, "Owner"));
  try {
    check_unit_fibres(fibres, 4, "Owner");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "Owner: 3 fibre directions for 4 quadrature points");
  }
  fibres[1] *= 1.001;
  try {
    check_unit_fibres(fibres, 3, "Owner");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "Owner: fibre direction 1 is not a finite unit vector");
  }
}

// sigma = F S F^T / J (thesis 5.41) against the direct formula, and a, lambda_f (thesis 5.30) for
// a stretch along the fibre followed by a rotation.
TEST(PointStress, CauchyStressAndDeformedFibre) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
  const Eigen::Matrix3d U = Eigen::Vector3d(1.2, 0.9, 0.95).asDiagonal();
  const Eigen::Matrix3d F = R * U;
  PointStress st;
  st.J = F.determinant();
  st.S << 3.0, 1.0, 0.5, 1.0, 2.0, -0.25, 0.5, -0.25, 1.0;
  st.fibre = Eigen::Vector3d::UnitX();
  complete_point_stress(F, st);
  const Eigen::Matrix3d expected = F * st.S * F.transpose() / F.determinant();
  EXPECT_LT((st.cauchy - expected).norm(), 1e-14 * expected.norm());
  EXPECT_NEAR(st.fibre_stretch, 1.2, 1e-15);
  EXPECT_LT((st.fibre_deformed - R.col(0)).norm(), 1e-15);
  Eigen::Matrix3d singular = F;
  singular.col(0).setZero();
  EXPECT_THROW(complete_point_stress(singular, st), std::runtime_error);
}

}  // namespace
}  // namespace isomuscle::continuum
