#include "plan/element_sets.hpp"

#include <algorithm>

namespace atssim::plan {

namespace {

ElementSet as_words(const ElementSet& s) {
  if (s.element_bytes == 4) return s;
  const std::int32_t per = static_cast<std::int32_t>(s.element_bytes / 4);
  ElementSet w{s.buffer, 4, {}};
  w.indices.reserve(s.indices.size() * per);
  for (std::int32_t i : s.indices) {
    for (std::int32_t k = 0; k < per; ++k) w.indices.push_back(i * per + k);
  }
  return w;
}

std::vector<std::int32_t> merged(const std::vector<std::int32_t>& a, const std::vector<std::int32_t>& b) {
  std::vector<std::int32_t> out;
  out.reserve(a.size() + b.size());
  std::set_union(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}

}  // namespace

bool ElementSet::contiguous() const {
  return !indices.empty() && indices.back() - indices.front() + 1 == static_cast<std::int32_t>(indices.size());
}

bool operator==(const ElementSet& a, const ElementSet& b) {
  return a.buffer == b.buffer && a.element_bytes == b.element_bytes && a.indices == b.indices;
}

void ElementSets::add(const ElementSet& set) {
  if (set.indices.empty()) return;
  auto at = std::lower_bound(sets_.begin(), sets_.end(), set.buffer,
                             [](const ElementSet& s, BufferId b) { return s.buffer < b; });
  if (at == sets_.end() || at->buffer != set.buffer) {
    sets_.insert(at, set);
    return;
  }
  if (at->element_bytes == set.element_bytes) {
    at->indices = merged(at->indices, set.indices);
    return;
  }
  const ElementSet mine = as_words(*at), theirs = as_words(set);
  at->element_bytes = 4;
  at->indices = merged(mine.indices, theirs.indices);
}

void ElementSets::add(const ElementSets& other) {
  for (const ElementSet& s : other.sets_) add(s);
}

std::size_t ElementSets::bytes() const {
  std::size_t n = 0;
  for (const ElementSet& s : sets_) n += s.bytes();
  return n;
}

ElementSets written_elements(const KernelLaunch& launch, std::span<const char> writable,
                             std::span<const std::size_t> buffer_bytes) {
  ElementSets out;
  if (launch.range.count <= 0) return out;
  const std::int64_t first = launch.range.first, end = launch.range.first + launch.range.count;
  const auto limit = [&](BufferId b, std::uint32_t bytes) {
    return static_cast<std::int64_t>(buffer_bytes[static_cast<std::size_t>(b)] / bytes);
  };
  const auto whole = [&](BufferId b) {
    ElementSet s{b, 4, {}};
    for (std::int64_t w = 0; w < limit(b, 4); ++w) s.indices.push_back(static_cast<std::int32_t>(w));
    return s;
  };
  std::vector<BufferId> described;
  for (const WriteSpan& w : launch.writes) {
    described.push_back(w.buffer);
    ElementSet s{w.buffer, w.element_bytes, {}};
    switch (w.kind) {
      case WriteSpan::Kind::whole:
        s = whole(w.buffer);
        break;
      case WriteSpan::Kind::elements:
        for (std::int64_t e = first; e < end; ++e) {
          if (w.offset + e < limit(w.buffer, w.element_bytes))
            s.indices.push_back(static_cast<std::int32_t>(w.offset + e));
        }
        break;
      case WriteSpan::Kind::indexed:
        for (std::int64_t e = first; e < end; ++e) {
          for (std::int32_t k = 0; k < w.arity; ++k) {
            const std::int32_t i = (*w.table)[w.arity * e + k];
            if (i >= 0 && i < limit(w.buffer, w.element_bytes)) s.indices.push_back(i);
          }
        }
        std::sort(s.indices.begin(), s.indices.end());
        s.indices.erase(std::unique(s.indices.begin(), s.indices.end()), s.indices.end());
        break;
    }
    out.add(s);
  }
  for (std::size_t a = 0; a < launch.args.size() && a < writable.size(); ++a) {
    const KernelArg& arg = launch.args[a];
    if (arg.kind != KernelArg::Kind::buffer || !writable[a]) continue;
    if (std::find(described.begin(), described.end(), arg.buffer) != described.end()) continue;
    out.add(whole(arg.buffer));
  }
  return out;
}

}  // namespace atssim::plan
