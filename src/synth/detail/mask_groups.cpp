#include "synth/detail/mask_groups.hpp"

#include <algorithm>
#include <numeric>

#include <tbb/parallel_sort.h>

#include "core/error.hpp"

namespace tw::detail {
namespace {

bool mask_less(const std::uint64_t* a, const std::uint64_t* b, int words) {
  return std::lexicographical_compare(a, a + words, b, b + words);
}

// The index i in [0, count) whose mask_at(i) equals `key`, the masks in increasing order; -1
// when none does.
template <class MaskAt>
int index_of_mask(int count, MaskAt mask_at, const std::uint64_t* key, int words) {
  int low = 0, high = count;  // the first index whose mask is not less than key
  while (low < high) {
    const int middle = low + (high - low) / 2;
    if (mask_less(mask_at(middle), key, words))
      low = middle + 1;
    else
      high = middle;
  }
  if (low == count || !std::equal(key, key + words, mask_at(low))) return -1;
  return low;
}

}  // namespace

MaskRuns mask_runs(const std::uint64_t* masks, int count, int words) {
  auto mask = [&](std::int32_t v) { return masks + std::size_t(v) * words; };
  std::vector<std::int32_t> by_mask(static_cast<std::size_t>(count));
  std::iota(by_mask.begin(), by_mask.end(), 0);
  // Only the runs count, not the order within them: any sort gives the same runs.
  tbb::parallel_sort(by_mask.begin(), by_mask.end(), [&](std::int32_t a, std::int32_t b) {
    return mask_less(mask(a), mask(b), words);
  });
  MaskRuns out;
  out.words = words;
  out.run_of.resize(by_mask.size());
  for (int i = 0; i < count; ++i) {
    const std::int32_t v = by_mask[std::size_t(i)];
    if (i == 0 || !std::equal(mask(v), mask(v) + words, mask(by_mask[std::size_t(i) - 1]))) {
      out.run_size.push_back(0);
      out.run_masks.insert(out.run_masks.end(), mask(v), mask(v) + words);
    }
    out.run_of[std::size_t(v)] = out.runs() - 1;
    ++out.run_size.back();
  }
  return out;
}

int run_with_mask(const MaskRuns& runs, const std::uint64_t* key) {
  return index_of_mask(
      runs.runs(), [&](int run) { return runs.run_masks.data() + std::size_t(run) * runs.words; },
      key, runs.words);
}

MaskGroups group_runs_by_cost(const MaskRuns& runs,
                              const std::vector<std::int64_t>& previous_cost) {
  const int previous = int(previous_cost.size());
  if (runs.run_of.size() != previous_cost.size())
    fail("mask groups: {} positions in the mask runs for {} costs", runs.run_of.size(),
         previous_cost.size());
  std::vector<std::int32_t> order(static_cast<std::size_t>(previous));  // rank -> v
  std::iota(order.begin(), order.end(), 0);
  // (P, v) is a total order: the parallel sort gives the one result (on the device backend's
  // path between two row kernels, so its time is the host's part of a row).
  tbb::parallel_sort(order.begin(), order.end(), [&](std::int32_t a, std::int32_t b) {
    return previous_cost[a] != previous_cost[b] ? previous_cost[a] < previous_cost[b] : a < b;
  });
  // Groups are the runs, numbered in increasing lowest rank; members in increasing rank.
  const int words = runs.words;
  MaskGroups out;
  out.words = words;
  out.groups_by_mask.assign(std::size_t(runs.runs()), -1);
  out.group_begin.reserve(std::size_t(runs.runs()) + 1);
  out.group_masks.reserve(runs.run_masks.size());
  std::int32_t next_begin = 0;
  for (std::int32_t v : order) {
    const std::int32_t run = runs.run_of[std::size_t(v)];
    if (out.groups_by_mask[std::size_t(run)] >= 0) continue;
    out.groups_by_mask[std::size_t(run)] = std::int32_t(out.group_begin.size());
    out.group_begin.push_back(next_begin);
    next_begin += runs.run_size[std::size_t(run)];
    const std::uint64_t* mask = runs.run_masks.data() + std::size_t(run) * words;
    out.group_masks.insert(out.group_masks.end(), mask, mask + words);
  }
  std::vector<std::int32_t> fill = out.group_begin;
  out.group_begin.push_back(previous);
  out.position.resize(order.size());
  for (std::int32_t v : order) {
    const std::int32_t g = out.groups_by_mask[std::size_t(runs.run_of[std::size_t(v)])];
    out.position[std::size_t(fill[std::size_t(g)]++)] = v;
  }
  return out;
}

MaskGroups group_by_mask(const std::vector<std::int64_t>& previous_cost, const std::uint64_t* masks,
                         int words) {
  return group_runs_by_cost(mask_runs(masks, int(previous_cost.size()), words), previous_cost);
}

int group_with_mask(const MaskGroups& groups, const std::uint64_t* key) {
  auto group_mask = [&](int g) {
    return groups.group_masks.data() + std::size_t(g) * groups.words;
  };
  // groups_by_mask lists the groups in increasing mask.
  const int found = index_of_mask(
      int(groups.groups_by_mask.size()),
      [&](int i) { return group_mask(groups.groups_by_mask[std::size_t(i)]); }, key, groups.words);
  return found < 0 ? -1 : groups.groups_by_mask[std::size_t(found)];
}

}  // namespace tw::detail
