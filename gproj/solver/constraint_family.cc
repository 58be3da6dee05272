#include "gproj/solver/constraint_family.h"

#include <cassert>

namespace gproj {

double RowWeight(FamilyRole role, double weight, double fairness_weight, double soft_scale) {
  switch (role) {
    case FamilyRole::kConstraint:
      return weight;
    case FamilyRole::kSoft:
      return weight * soft_scale;
    case FamilyRole::kFairness:
      return weight * fairness_weight * fairness_weight * soft_scale;
  }
  return weight;
}

ConstraintFamily::ConstraintFamily(std::string name, int rows_per_element, FamilyRole role,
                                   double weight)
    : name_(std::move(name)), rows_per_element_(rows_per_element), role_(role), weight_(weight) {
  assert(rows_per_element > 0);
}

int ConstraintFamily::AddElement(const std::vector<int>& items) {
  return AddElement(items.data(), static_cast<int>(items.size()));
}

int ConstraintFamily::AddElement(const int* items, int count) {
  assert(count > 0);
  items_.insert(items_.end(), items, items + count);
  element_begin_.push_back(static_cast<int>(items_.size()));
  return num_elements() - 1;
}

}  // namespace gproj
