#pragma once
// The long edges of a growing particle (shape/growing_mesh.h) by decreasing key: a small 4-ary
// heap of the longest ones over buckets of shorter ones by squared length. Internal to shape/.

#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace aggpack::detail {

// A max-priority queue of 128-bit keys whose high 64 bits are the bits of a positive double (an
// edge's squared length, > the limit given to reset) and whose `top` is always the largest key
// held: the sequence of keys it gives out depends on the keys alone, as for any exact priority
// queue.
//
// Why not one heap (bench/RESULTS.md, "Generator"): a heap of all long edges (hundreds at L/r
// 0.25, half of them stale) costs a sift through all its levels per pop, and growth pops about
// two keys per insertion. Here the keys are binned by their squared length (the top bits of the
// double: 256 bins per factor two), and only the bins at or above `level_` are in the
// heap; a shorter key is appended to its bin, unsorted, and enters the heap when the heap has
// run dry and its bin is the highest left. The bin of a key is a monotone function of the key,
// so every key in the heap is larger than every key in a bin: the heap's top is the largest key.
// The heap then holds a bin or two (a few keys), so a pop is a few comparisons.
class EdgeQueue {
 public:
  __extension__ using Key = unsigned __int128;

  // Empties the queue for keys above `limit_squared` (> 0), keeping its storage.
  void reset(double limit_squared) {
    for (std::size_t word = 0; word < used_.size(); ++word) {
      for (std::uint64_t bits = used_[word]; bits != 0; bits &= bits - 1) {
        bins_[64 * word + static_cast<std::size_t>(std::countr_zero(bits))].clear();
      }
      used_[word] = 0;
    }
    heap_.clear();
    base_ = std::bit_cast<std::uint64_t>(limit_squared) >> kShift;
    level_ = kNoLevel;  // the first top() takes the highest bin
  }

  [[nodiscard]] bool empty() const { return heap_.empty() && !has_bins(); }

  // Always inlined: GCC kept it out of line (the bin's append has a reallocating path), a call
  // per push (-0.8 % instructions of the hull growth).
  [[gnu::always_inline]] void push(Key key) {
    const std::size_t bin = bin_of(key);
    if (bin >= level_) {
      push_heap(key);
      return;
    }
    if (bin >= bins_.size()) grow(bin);
    bins_[bin].push_back(key);
    used_[bin / 64] |= std::uint64_t{1} << (bin % 64);
  }

  // The largest key held (the queue must not be empty).
  Key top() {
    if (heap_.empty()) refill();
    return heap_.front();
  }

  // Removes top()'s key.
  void pop() {
    if (heap_.empty()) refill();
    pop_heap();
  }

 private:
  static constexpr unsigned kShift = 44;  // 2^(52 - 44) = 256 bins per octave of squared length

  [[nodiscard]] std::size_t bin_of(Key key) const {
    return static_cast<std::size_t>((static_cast<std::uint64_t>(key >> 64U) >> kShift) - base_);
  }
  static constexpr std::size_t kNoLevel = ~std::size_t{0};

  void grow(std::size_t bin) {
    bins_.resize(64 * (bin / 64 + 1));
    used_.resize(bins_.size() / 64, 0);
  }

  [[nodiscard]] bool has_bins() const {
    for (const std::uint64_t word : used_) {
      if (word != 0) return true;
    }
    return false;
  }

  // The heap ran dry: the highest non-empty bin becomes the heap (its keys are all below the
  // level, and above every other bin's).
  void refill() {
    // Bins at or above level_ are empty (their keys go to the heap): the scan starts at level_.
    std::size_t word = level_ == kNoLevel ? used_.size() : level_ / 64 + 1;
    while (used_[word - 1] == 0) --word;  // not empty: some bin is used
    --word;
    const std::size_t bin =
        64 * word + 63 - static_cast<std::size_t>(std::countl_zero(used_[word]));
    used_[word] &= ~(std::uint64_t{1} << (bin % 64));
    level_ = bin;
    for (const Key key : bins_[bin]) push_heap(key);
    bins_[bin].clear();
  }

  // Heap of the keys at or above level_'s bin (4-ary: children of i are 4 i + 1 .. 4 i + 4).
  void push_heap(Key key) {
    std::size_t hole = heap_.size();
    heap_.push_back(key);
    Key* heap = heap_.data();
    while (hole > 0) {
      const std::size_t parent = (hole - 1) / 4;
      if (!(heap[parent] < key)) break;
      heap[hole] = heap[parent];
      hole = parent;
    }
    heap[hole] = key;
  }

  void pop_heap() {
    // The root's hole goes down to a leaf along the largest children, then the last key sifts up
    // from there (it nearly always belongs near the bottom).
    const Key last = heap_.back();
    heap_.pop_back();
    const std::size_t size = heap_.size();
    if (size == 0) return;
    Key* heap = heap_.data();
    std::size_t hole = 0;
    for (;;) {
      const std::size_t first = 4 * hole + 1;
      if (first + 4 <= size) {
        const std::size_t a = first + static_cast<std::size_t>(heap[first] < heap[first + 1]);
        const std::size_t b =
            first + 2 + static_cast<std::size_t>(heap[first + 2] < heap[first + 3]);
        const std::size_t child = heap[a] < heap[b] ? b : a;
        heap[hole] = heap[child];
        hole = child;
        continue;
      }
      if (first >= size) break;
      std::size_t child = first;
      for (std::size_t c = first + 1; c < size; ++c) {
        if (heap[child] < heap[c]) child = c;
      }
      heap[hole] = heap[child];
      hole = child;
      break;
    }
    while (hole > 0) {
      const std::size_t parent = (hole - 1) / 4;
      if (!(heap[parent] < last)) break;
      heap[hole] = heap[parent];
      hole = parent;
    }
    heap[hole] = last;
  }

  std::vector<Key> heap_;
  std::vector<std::vector<Key>> bins_;
  std::vector<std::uint64_t> used_;  // bit b: bin b holds keys
  std::uint64_t base_ = 0;           // the limit's bin, in the double's bits
  std::size_t level_ = 0;            // bins at or above this one are in the heap
};

}  // namespace aggpack::detail
