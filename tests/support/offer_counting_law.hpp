#pragma once
// A material law that forwards to another and counts the evaluations offered a current trial
// history (materials::PointInput::trial_is_current); with refuse = true it evaluates those afresh
// instead. Used by the tests of the IGA and tetrahedral problems' tangent pass.
#include <atomic>
#include <span>
#include <string>

#include "materials/material_law.hpp"

namespace isomuscle::test_support {

class OfferCountingLaw final : public materials::MaterialLaw {
 public:
  OfferCountingLaw(const MaterialLaw& inner, bool refuse) : inner_(inner), refuse_(refuse) {}
  mutable std::atomic<long> offered{0};

  std::string name() const override { return inner_.name(); }
  int history_size() const override { return inner_.history_size(); }
  bool uses_fibre() const override { return inner_.uses_fibre(); }
  void initial_history(std::span<double> h) const override { inner_.initial_history(h); }
  materials::PointStatus evaluate(const materials::PointInput& in, materials::PointResult& out,
                                  bool tangent) const override {
    return inner_.evaluate(count(in), out, tangent);
  }
  bool has_volumetric_split() const override { return inner_.has_volumetric_split(); }
  materials::PointStatus evaluate_isochoric(const materials::PointInput& in,
                                            materials::PointResult& out,
                                            bool tangent) const override {
    return inner_.evaluate_isochoric(count(in), out, tangent);
  }
  Eigen::Vector3d volumetric(double J) const override { return inner_.volumetric(J); }
  double shear_modulus() const override { return inner_.shear_modulus(); }
  double bulk_modulus() const override { return inner_.bulk_modulus(); }
  double activation(double time) const override { return inner_.activation(time); }

 private:
  materials::PointInput count(const materials::PointInput& in) const {
    offered += in.trial_is_current ? 1 : 0;
    materials::PointInput copy = in;
    copy.trial_is_current = in.trial_is_current && !refuse_;
    return copy;
  }
  const MaterialLaw& inner_;
  bool refuse_;
};

}  // namespace isomuscle::test_support
