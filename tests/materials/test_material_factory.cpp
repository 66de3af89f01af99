// The factory: model and parameter names, defaults from the thesis tables, ranges, and messages
// that name the parameter, the value and the valid range or choices.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "materials/hill_muscle.hpp"
#include "materials/material_factory.hpp"

namespace isomuscle::materials {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

std::string message_of(const std::string& model, const std::map<std::string, double>& params) {
  try {
    make_material(model, params);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no exception";
}

TEST(MaterialFactory, ModelsAndDefaultsAreValid) {
  EXPECT_THAT(material_models(),
              ::testing::ElementsAre("lu2010", "tang2009", "neo_hookean", "linear_elastic"));
  for (const std::string& model : material_models()) {
    for (const ParameterSpec& s : material_parameters(model)) {
      EXPECT_TRUE(in_range(s, s.default_value)) << model << " " << s.name;
      EXPECT_FALSE(s.description.empty()) << model << " " << s.name;
    }
    const auto law = make_material(model);
    EXPECT_EQ(law->name(), model);
    EXPECT_EQ(law->history_names().size(), static_cast<std::size_t>(law->history_size()));
    EXPECT_GT(law->shear_modulus(), 0.0);
    EXPECT_GT(law->bulk_modulus(), law->shear_modulus());
  }
}

TEST(MaterialFactory, MuscleDefaultsAreThesisTables) {
  const auto lu = make_material("lu2010");
  const auto& l = dynamic_cast<const HillMuscle&>(*lu).parameters();
  EXPECT_EQ(l.b, 23.46);
  EXPECT_EQ(l.c, 379.0);
  EXPECT_EQ(l.D, 1.0e-9);
  EXPECT_EQ(l.fibre.alpha, 10.0);
  EXPECT_EQ(l.fibre.beta, 1.0e3);
  EXPECT_EQ(l.fibre.A, 4.0);
  EXPECT_EQ(l.fibre.sigma0, 7.0e5);
  EXPECT_EQ(l.fibre.activation.rate, 50.0);
  EXPECT_EQ(l.fibre.k_c, 5.0);
  EXPECT_EQ(l.fibre.k_e, 5.0);
  EXPECT_EQ(l.fibre.d, 1.5);
  EXPECT_EQ(l.fibre.v_max, 17.0);
  EXPECT_EQ(l.fibre.lambda_opt, 1.05);
  EXPECT_EQ(l.fibre.k, 0.3);
  EXPECT_EQ(lu->history_names(),
            (std::vector<std::string>{"lambda_s", "lambda_m", "delta_lambda_m", "lambda_f",
                                      "see_rate", "fibre_rate", "see_stress", "see_stiffness"}));
  EXPECT_EQ(lu->cauchy_part_names(), (std::vector<std::string>{"see", "pe", "matrix", "vol"}));
  EXPECT_TRUE(lu->uses_fibre());
  EXPECT_TRUE(lu->has_volumetric_split());

  const auto tang = make_material("tang2009");
  const auto& t = dynamic_cast<const HillMuscle&>(*tang).parameters();
  EXPECT_EQ(t.b, 1.79);
  EXPECT_EQ(t.c, 821.0);
  EXPECT_EQ(t.fibre.alpha, 100.0);
  EXPECT_EQ(t.fibre.beta, 0.1);
  EXPECT_EQ(t.fibre.d, 1.65);
  EXPECT_EQ(t.fibre.k_e, 3.14);
  EXPECT_EQ(t.fibre.v_max, 2.0);
  EXPECT_EQ(t.fibre.sigma0, 2.2e5);
  EXPECT_EQ(t.fibre.a_v, 7.0e4);
  // Chapter-5 activation: full after 0.005 s, held.
  EXPECT_EQ(tang->activation(0.005), 1.0);
  EXPECT_EQ(tang->activation(0.2), 1.0);
  EXPECT_GT(tang->activation(0.0025), 0.0);
  EXPECT_LT(tang->activation(0.0025), 1.0);
  EXPECT_EQ(make_material("neo_hookean")->activation(1.0), 0.0);
}

TEST(MaterialFactory, BadParametersNameParameterValueAndRange) {
  EXPECT_THAT(
      message_of("lu2010", {{"D", -1e-9}}),
      AllOf(HasSubstr("lu2010"), HasSubstr("'D'"), HasSubstr("-1e-09"), HasSubstr("(0, inf)")));
  EXPECT_THAT(message_of("lu2010", {{"lambda_opt", 0.0}}),
              AllOf(HasSubstr("'lambda_opt'"), HasSubstr("= 0"), HasSubstr("(0, inf)")));
  EXPECT_THAT(message_of("tang2009", {{"lambda_opt", -1.0}}), HasSubstr("'lambda_opt'"));
  EXPECT_THAT(message_of("lu2010", {{"sigma0", -5.0}}),
              AllOf(HasSubstr("'sigma0'"), HasSubstr("[0, inf)")));
  EXPECT_THAT(message_of("lu2010", {{"lambda_dot_min", 0.0}}),
              AllOf(HasSubstr("'lambda_dot_min'"), HasSubstr("(-inf, 0)")));
  EXPECT_THAT(message_of("lu2010", {{"d", 0.9}}), AllOf(HasSubstr("'d'"), HasSubstr("[1, inf)")));
  EXPECT_THAT(message_of("lu2010", {{"frozen_ce_tangent", 0.5}}),
              AllOf(HasSubstr("'frozen_ce_tangent'"), HasSubstr("0 or 1")));
  EXPECT_THAT(message_of("linear_elastic", {{"nu", 0.5}}),
              AllOf(HasSubstr("'nu'"), HasSubstr("(-1, 0.5)")));
  EXPECT_THAT(message_of("neo_hookean", {{"K", std::numeric_limits<double>::quiet_NaN()}}),
              HasSubstr("'K'"));
  EXPECT_THAT(message_of("lu2010", {{"t0", 0.5}, {"t1", 0.2}}),
              AllOf(HasSubstr("'t1'"), HasSubstr("t1 >= t0")));
  // A parameter at the edge of a closed range is accepted; t1 = inf is the default.
  EXPECT_NO_THROW(make_material("lu2010", {{"sigma0", 0.0}, {"d", 1.0}, {"n2", 1.0}}));
}

TEST(MaterialFactory, UnknownNamesListTheValidChoices) {
  EXPECT_THAT(message_of("hill", {}),
              AllOf(HasSubstr("'hill'"), HasSubstr("lu2010"), HasSubstr("tang2009"),
                    HasSubstr("neo_hookean"), HasSubstr("linear_elastic")));
  EXPECT_THAT(message_of("lu2010", {{"sigma_0", 1.0}}),
              AllOf(HasSubstr("'sigma_0'"), HasSubstr("sigma0"), HasSubstr("lambda_opt"),
                    HasSubstr("frozen_ce_tangent")));
  EXPECT_THROW(material_parameters("nope"), std::invalid_argument);
  // A law without a split says so.
  EXPECT_EQ(describe_range(material_parameters("lu2010").front()), "(0, inf)");
}

}  // namespace
}  // namespace isomuscle::materials
