// Deliberately breaks the core's rules: proves the symbol check catches an allocation.
#include <vector>

int CanaryAllocates(int n) {
  std::vector<int> v(static_cast<unsigned>(n), 1);
  return v.empty() ? 0 : v.back();
}
