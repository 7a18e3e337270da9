// A one-line progress bar on stderr, drawn only when stderr is a terminal.
#pragma once

#include <cstdio>
#include <string>
#include <unistd.h>

namespace dpcr::apps {

class Progress {
 public:
  explicit Progress(std::string label) : label_(std::move(label)), enabled_(isatty(STDERR_FILENO) != 0) {}
  // fraction in [0, 1]; redraws at most every 1 %.
  void Update(double fraction, const char* detail = "") {
    if (!enabled_) return;
    const int pct = static_cast<int>(fraction * 100.0);
    if (pct == last_) return;
    last_ = pct;
    const int filled = pct * 30 / 100;
    std::fprintf(stderr, "\r%s [%.*s%*s] %3d%% %s", label_.c_str(), filled, "##############################",
                 30 - filled, "", pct, detail);
    std::fflush(stderr);
  }
  void Done() {
    if (enabled_ && last_ >= 0) std::fprintf(stderr, "\n");
  }

 private:
  std::string label_;
  bool enabled_;
  int last_ = -1;
};

}  // namespace dpcr::apps
