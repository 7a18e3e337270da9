// Map saves off the scan loop. The loop copies the map file's bytes into the worker's buffer
// (allocated once at start-up: the largest map the profile can write), which is CPU work bounded
// by that size; the worker thread then stores them (open, write, fsync, rename, fsync the
// directory: the calls that wait for the flash) while the loop keeps reading the devices.
// One save at a time: the buffer belongs to the loop only while the worker is idle.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "hal/ports.hpp"

namespace dpcr::board {

struct SaveOutcome {
  bool ok = false;
  std::size_t bytes = 0;
  char error[256] = {};  // "file: step: reason" when !ok
};

class SaveWorker {
 public:
  SaveWorker() = default;
  ~SaveWorker();  // lets a save in progress finish, then stops the thread
  SaveWorker(const SaveWorker&) = delete;
  SaveWorker& operator=(const SaveWorker&) = delete;

  // Allocates the buffer and starts the thread: the worker's only allocations. A failed write's
  // reason is the store's (AtomicFileStore::last_error) or the errno's. False with the reason.
  bool Start(BlobStore* store, std::size_t capacity, std::string* error);
  bool started() const { return thread_.joinable(); }

  // True when the buffer is the loop's: no save queued or being written.
  bool idle() const { return state_.load(std::memory_order_acquire) == kIdle; }
  std::uint8_t* buffer() { return buffer_.get(); }
  std::size_t capacity() const { return capacity_; }
  // Hands the first `size` bytes of the buffer over as blob `name` (a string literal: kept by
  // pointer). Only while idle().
  void Submit(const char* name, std::size_t size);
  // The outcome of a finished save, once: false while none finished since the last call.
  bool TakeResult(SaveOutcome* out);
  // Waits until a queued or running save has finished (exit path only: this blocks).
  void WaitIdle();
  // Saves finished since start (for tests and the counters).
  std::uint32_t saves_done() const { return saves_done_.load(); }

 private:
  enum State : int { kIdle, kQueued, kWriting, kDone };
  void Run();

  BlobStore* store_ = nullptr;
  std::unique_ptr<std::uint8_t[]> buffer_;
  std::size_t capacity_ = 0;
  const char* name_ = nullptr;
  std::size_t size_ = 0;
  SaveOutcome outcome_;
  std::atomic<int> state_{kIdle};
  std::atomic<std::uint32_t> saves_done_{0};
  bool stop_ = false;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread thread_;
};

}  // namespace dpcr::board
