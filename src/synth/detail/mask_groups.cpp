#include "synth/detail/mask_groups.hpp"

#include <algorithm>
#include <numeric>

namespace tw::detail {
namespace {

bool mask_less(const std::uint64_t* a, const std::uint64_t* b, int words) {
  return std::lexicographical_compare(a, a + words, b, b + words);
}

}  // namespace

MaskGroups group_by_mask(const std::vector<std::int64_t>& previous_cost, const std::uint64_t* masks,
                         int words) {
  const int previous = int(previous_cost.size());
  std::vector<std::int32_t> order(static_cast<std::size_t>(previous));  // rank -> v
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::int32_t a, std::int32_t b) {
    return previous_cost[a] != previous_cost[b] ? previous_cost[a] < previous_cost[b] : a < b;
  });
  auto mask = [&](int rank) { return masks + std::size_t(order[std::size_t(rank)]) * words; };
  std::vector<std::int32_t> ranks(order.size());
  std::iota(ranks.begin(), ranks.end(), 0);
  std::sort(ranks.begin(), ranks.end(), [&](std::int32_t a, std::int32_t b) {
    if (mask_less(mask(a), mask(b), words)) return true;
    if (mask_less(mask(b), mask(a), words)) return false;
    return a < b;
  });
  // Runs of equal masks, each starting at its lowest rank; then groups by that rank.
  std::vector<std::int32_t> run_begin;
  for (int i = 0; i < previous; ++i)
    if (i == 0 || !std::equal(mask(ranks[i]), mask(ranks[i]) + words, mask(ranks[i - 1])))
      run_begin.push_back(i);
  const int groups = int(run_begin.size());
  run_begin.push_back(previous);
  std::vector<std::int32_t> by_min_rank(static_cast<std::size_t>(groups));
  std::iota(by_min_rank.begin(), by_min_rank.end(), 0);
  std::sort(by_min_rank.begin(), by_min_rank.end(),
            [&](int a, int b) { return ranks[run_begin[a]] < ranks[run_begin[b]]; });

  MaskGroups out;
  out.words = words;
  out.position.reserve(order.size());
  out.group_begin.reserve(std::size_t(groups) + 1);
  out.groups_by_mask.assign(std::size_t(groups), 0);
  out.group_masks.reserve(std::size_t(groups) * words);
  for (int g = 0; g < groups; ++g) {
    const int run = by_min_rank[std::size_t(g)];
    out.groups_by_mask[std::size_t(run)] = g;  // runs are in mask order
    out.group_begin.push_back(std::int32_t(out.position.size()));
    out.group_masks.insert(out.group_masks.end(), mask(ranks[run_begin[run]]),
                           mask(ranks[run_begin[run]]) + words);
    for (int i = run_begin[run]; i < run_begin[run + 1]; ++i)
      out.position.push_back(order[ranks[i]]);
  }
  out.group_begin.push_back(previous);
  return out;
}

int group_with_mask(const MaskGroups& groups, const std::uint64_t* key) {
  const int words = groups.words;
  auto group_mask = [&](int g) { return groups.group_masks.data() + std::size_t(g) * words; };
  const auto it =
      std::lower_bound(groups.groups_by_mask.begin(), groups.groups_by_mask.end(), 0,
                       [&](std::int32_t g, int) { return mask_less(group_mask(g), key, words); });
  if (it == groups.groups_by_mask.end() || !std::equal(key, key + words, group_mask(*it)))
    return -1;
  return *it;
}

}  // namespace tw::detail
