#pragma once
// The unknowns of a gproj problem: one flat vector x, laid out in named blocks of items.
// An item is a small group of scalars that belong together (a vertex: 3, a face normal: 3);
// constraint elements name the items they touch, and the Ceres adapter makes each item one
// parameter block.

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace gproj {

struct VariableBlock {
  std::string name;
  int num_items = 0;   // e.g. #V
  int item_dim = 0;    // e.g. 3
  int first_item = 0;  // global item id of item 0
  int offset = 0;      // index in x of the block's first scalar
  // Per-element auxiliaries (a face normal, one sample's curvature values): no row touches two
  // items of such a block, so the solver may eliminate them first (Schur complement).
  bool eliminable = false;
  int size() const { return num_items * item_dim; }
};

class VariableLayout {
 public:
  // Appends a block of `num_items` items of `item_dim` scalars; returns the block id.
  int AddBlock(const std::string& name, int num_items, int item_dim, bool eliminable = false);

  int num_blocks() const { return static_cast<int>(blocks_.size()); }
  int num_items() const { return static_cast<int>(item_offsets_.size()) - 1; }
  int num_variables() const { return item_offsets_.back(); }
  const VariableBlock& block(int id) const { return blocks_[id]; }
  // Block id by name, or -1.
  int FindBlock(const std::string& name) const;
  // Block id of a global item id, or -1 when there is no such item.
  int BlockOfItem(int item) const;

  // Global item id of item i of block b.
  int Item(int b, int i) const { return blocks_[b].first_item + i; }
  int ItemOffset(int item) const { return item_offsets_[item]; }
  int ItemDim(int item) const { return item_offsets_[item + 1] - item_offsets_[item]; }
  // Index in x of component c of item i of block b.
  int Index(int b, int i, int c) const { return blocks_[b].offset + i * blocks_[b].item_dim + c; }

 private:
  std::vector<VariableBlock> blocks_;
  std::vector<int> item_offsets_ = {0};  // #items + 1
};

// The global item ids of one block, named by element: items[i] for item i, items[h] for anything
// with idx() (a mesh handle: items[vertex], items[face]), items(i, j, ...) for several at once,
// in the spirit of TinyAD's element.variables(handle). A term's Add refuses ids outside the
// layout, so no check is made here.
class BlockItems {
 public:
  BlockItems(const VariableLayout& layout, int block)
      : first_(layout.block(block).first_item), size_(layout.block(block).num_items) {}

  int operator[](int i) const { return first_ + i; }
  template <typename Handle, typename = decltype(std::declval<const Handle&>().idx())>
  int operator[](const Handle& h) const {
    return first_ + h.idx();
  }
  template <typename... Index>
  std::array<int, sizeof...(Index)> operator()(const Index&... i) const {
    return {(*this)[i]...};
  }
  int size() const { return size_; }

 private:
  int first_, size_;
};

}  // namespace gproj
