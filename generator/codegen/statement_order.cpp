// SPDX-License-Identifier: GPL-2.0-or-later
#include "codegen/statement_order.hpp"

#include <queue>
#include <stdexcept>
#include <utility>

namespace kanegen::codegen {

std::vector<int> shorten_live_ranges(const std::vector<OrderedStatement>& statements) {
  const int n = static_cast<int>(statements.size());
  std::vector<std::vector<int>> readers(n);
  std::vector<int> waiting(n, 0);  // operands not yet computed
  for (int i = 0; i < n; ++i) {
    for (int r : statements[i].reads) {
      if (r < 0 || r >= i) throw std::logic_error("statement order: a statement reads a later one");
      readers[r].push_back(i);
    }
    waiting[i] = static_cast<int>(statements[i].reads.size());
  }
  std::vector<int> unread(n);  // readers not yet placed
  for (int i = 0; i < n; ++i) unread[i] = static_cast<int>(readers[i].size());
  std::vector<bool> placed(n, false);
  auto score = [&](int i) {
    int ends = 0;
    for (int r : statements[i].reads) ends += unread[r] == 1 ? 1 : 0;
    return ends - (statements[i].defines ? 1 : 0);
  };
  // Highest score first, then the earliest statement. A statement's score
  // only grows while it waits (its operands' other readers are placed), so
  // an entry whose score is no longer current is skipped when it comes up.
  using Entry = std::pair<int, int>;  // (score, -index)
  std::priority_queue<Entry> ready;
  std::vector<int> current(n, 0);
  auto push = [&](int i) {
    current[i] = score(i);
    ready.push({current[i], -i});
  };
  for (int i = 0; i < n; ++i)
    if (waiting[i] == 0) push(i);
  std::vector<int> order;
  order.reserve(n);
  while (!ready.empty()) {
    const auto [s, minus_i] = ready.top();
    ready.pop();
    const int i = -minus_i;
    if (placed[i] || s != current[i]) continue;
    placed[i] = true;
    order.push_back(i);
    for (int r : statements[i].reads)
      if (--unread[r] == 1)  // the one reader left now ends r's range
        for (int last : readers[r])
          if (!placed[last] && waiting[last] == 0) push(last);
    for (int next : readers[i])
      if (--waiting[next] == 0) push(next);
  }
  if (static_cast<int>(order.size()) != n) throw std::logic_error("statement order: a cycle");
  return order;
}

}  // namespace kanegen::codegen
