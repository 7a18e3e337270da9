// Crash-safe file replacement: write a temp file in the same directory, fsync it, rename it
// over the target, fsync the directory. A reader sees the old file or the new one, never a mix.
#pragma once

#include <cstddef>
#include <string>

namespace dpcr::board {

// False with "path: step: strerror" in `error`; the previous file is untouched on failure.
bool WriteFileAtomic(const std::string& path, const void* data, std::size_t size, std::string* error);

}  // namespace dpcr::board
