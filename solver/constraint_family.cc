#include "solver/constraint_family.h"

#include <cassert>

namespace gproj {

ConstraintFamily::ConstraintFamily(std::string name, int rows_per_element, FamilyRole role,
                                   double weight)
    : name_(std::move(name)), rows_per_element_(rows_per_element), role_(role), weight_(weight) {
  assert(rows_per_element > 0);
}

int ConstraintFamily::AddElement(const std::vector<int>& items) {
  assert(!items.empty());
  items_.insert(items_.end(), items.begin(), items.end());
  element_begin_.push_back(static_cast<int>(items_.size()));
  return num_elements() - 1;
}

}  // namespace gproj
