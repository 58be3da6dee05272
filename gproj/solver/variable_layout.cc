#include "gproj/solver/variable_layout.h"

#include <cassert>

namespace gproj {

int VariableLayout::AddBlock(const std::string& name, int num_items, int item_dim,
                             bool eliminable) {
  assert(num_items >= 0 && item_dim > 0);
  assert(FindBlock(name) < 0);
  VariableBlock b;
  b.name = name;
  b.num_items = num_items;
  b.item_dim = item_dim;
  b.eliminable = eliminable;
  b.first_item = this->num_items();
  b.offset = num_variables();
  for (int i = 0; i < num_items; ++i) item_offsets_.push_back(item_offsets_.back() + item_dim);
  blocks_.push_back(b);
  return num_blocks() - 1;
}

int VariableLayout::BlockOfItem(int item) const {
  if (item < 0 || item >= num_items()) return -1;
  for (int b = num_blocks() - 1; b >= 0; --b)
    if (item >= blocks_[b].first_item) return b;
  return -1;
}

int VariableLayout::FindBlock(const std::string& name) const {
  for (int b = 0; b < num_blocks(); ++b)
    if (blocks_[b].name == name) return b;
  return -1;
}

}  // namespace gproj
