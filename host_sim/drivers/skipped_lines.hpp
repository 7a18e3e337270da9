// Lines of a recording (UART capture, candump log) that did not parse and were skipped so that
// the rest could be read: a flipped byte loses its line, not the file.
#pragma once

#include <string>
#include <utility>

namespace dpcr {

struct SkippedLines {
  int count = 0;
  std::string first;  // "file:line: reason" of the first one
  void Add(std::string message) {
    if (count++ == 0) first = std::move(message);
  }
};

// A reader's answer to a bad line: with `skipped`, counted there and the reading goes on (true);
// without, `message` is the reader's error (false).
inline bool SkipBadLine(SkippedLines* skipped, std::string message, std::string* error) {
  if (skipped == nullptr) {
    *error = std::move(message);
    return false;
  }
  skipped->Add(std::move(message));
  return true;
}

}  // namespace dpcr
