#include "gproj/solver/constraint_family.h"

#include <cassert>
#include <stdexcept>
#include <string>

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
  const auto refuse = [&](int k, const std::string& why) {
    throw std::invalid_argument("family '" + name_ + "', element " +
                                std::to_string(num_elements()) + ": item " + std::to_string(k) +
                                " (id " + std::to_string(items[k]) + ") " + why);
  };
  if (!item_dims_.empty() && count != static_cast<int>(item_dims_.size()))
    throw std::invalid_argument("family '" + name_ + "', element " +
                                std::to_string(num_elements()) + ": " + std::to_string(count) +
                                " items, the family takes " + std::to_string(item_dims_.size()));
  for (int k = 0; layout_ != nullptr && k < count; ++k) {
    const int block = layout_->BlockOfItem(items[k]);
    if (block < 0)
      refuse(k, "is not in the layout (it has " + std::to_string(layout_->num_items()) + " items)");
    if (!item_dims_.empty() && layout_->ItemDim(items[k]) != item_dims_[k])
      refuse(k, "of block '" + layout_->block(block).name + "' has " +
                    std::to_string(layout_->ItemDim(items[k])) + " scalars; the family takes " +
                    std::to_string(item_dims_[k]));
  }
  items_.insert(items_.end(), items, items + count);
  element_begin_.push_back(static_cast<int>(items_.size()));
  return num_elements() - 1;
}

}  // namespace gproj
