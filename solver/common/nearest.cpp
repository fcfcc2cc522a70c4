#include "solver/common/nearest.h"

#include <algorithm>
#include <cctype>
#include <numeric>

namespace skewbridge {
namespace {

char Lower(char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); }

// `name` without its last "_..." or "." part, or "" when it has none.
std::string_view Stem(std::string_view name) {
  const std::size_t cut = name.find_last_of("_.");
  if (cut == std::string_view::npos || cut == 0) {
    return {};
  }
  return name.substr(0, cut);
}

}  // namespace

std::size_t EditDistance(std::string_view a, std::string_view b) {
  // The Wagner-Fischer table row by row, row i holding distance(a[0, i), b[0, j)) for every j;
  // a swap of neighbours (cvs / csv) looks two rows back.
  std::vector<std::size_t> before(b.size() + 1), previous(b.size() + 1), row(b.size() + 1);
  std::iota(row.begin(), row.end(), std::size_t{0});
  for (std::size_t i = 1; i <= a.size(); ++i) {
    before.swap(previous);
    previous.swap(row);
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const bool same = Lower(a[i - 1]) == Lower(b[j - 1]);
      row[j] = std::min({previous[j] + 1, row[j - 1] + 1, previous[j - 1] + (same ? 0 : 1)});
      if (i > 1 && j > 1 && Lower(a[i - 1]) == Lower(b[j - 2]) &&
          Lower(a[i - 2]) == Lower(b[j - 1])) {
        row[j] = std::min(row[j], before[j - 2] + 1);
      }
    }
  }
  return row[b.size()];
}

std::size_t SlipDistance(std::string_view word, std::string_view name) {
  std::size_t d = EditDistance(word, name);
  if (const std::string_view stem = Stem(name); !stem.empty()) {
    d = std::min(d, EditDistance(word, stem) + 1);
  }
  if (const std::string_view stem = Stem(word); !stem.empty()) {
    d = std::min(d, EditDistance(stem, name) + 1);
  }
  return d;
}

std::vector<std::string> NearestNames(std::string_view word, const std::vector<std::string>& names,
                                      std::size_t max_count, bool plausible_only) {
  std::vector<std::pair<std::size_t, std::size_t>> ranked;  // (distance, index in names)
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::size_t d = SlipDistance(word, names[i]);
    const std::size_t longer = std::max(word.size(), names[i].size());
    if (!plausible_only || d <= std::max<std::size_t>(1, longer / 3)) {
      ranked.emplace_back(d, i);
    }
  }
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<std::string> out;
  for (std::size_t k = 0; k < ranked.size() && k < max_count; ++k) {
    out.push_back(names[ranked[k].second]);
  }
  return out;
}

std::string DidYouMean(std::string_view word, const std::vector<std::string>& names) {
  const std::vector<std::string> nearest = NearestNames(word, names, 1, true);
  return nearest.empty() ? std::string() : "; did you mean `" + nearest.front() + "`?";
}

}  // namespace skewbridge
