#include "board/save_worker.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "board/atomic_file.hpp"

namespace dpcr::board {

SaveWorker::~SaveWorker() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

bool SaveWorker::Start(BlobStore* store, std::size_t capacity, std::string* error) {
  store_ = store;
  buffer_.reset(new (std::nothrow) std::uint8_t[capacity]);
  if (!buffer_) {
    *error = "save buffer of " + std::to_string(capacity) + " bytes: out of memory";
    return false;
  }
  capacity_ = capacity;
  std::memset(buffer_.get(), 0, capacity);  // touched now: the pages are resident before the loop runs
  try {
    thread_ = std::thread([this] { Run(); });
  } catch (const std::system_error& e) {
    *error = std::string("save thread: ") + e.what();
    return false;
  }
  return true;
}

void SaveWorker::Submit(const char* name, std::size_t size) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    name_ = name;
    size_ = size;
    state_.store(kQueued, std::memory_order_release);
  }
  wake_.notify_one();
}

bool SaveWorker::TakeResult(SaveOutcome* out) {
  if (state_.load(std::memory_order_acquire) != kDone) return false;
  *out = outcome_;
  state_.store(kIdle, std::memory_order_release);
  return true;
}

void SaveWorker::WaitIdle() {
  std::unique_lock<std::mutex> lock(mutex_);
  wake_.wait(lock, [this] {
    const int s = state_.load(std::memory_order_acquire);
    return s == kIdle || s == kDone;
  });
}

void SaveWorker::Run() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stop_ || state_.load(std::memory_order_acquire) == kQueued; });
    if (state_.load(std::memory_order_acquire) != kQueued) return;  // stop, nothing queued
    state_.store(kWriting, std::memory_order_release);
    const char* name = name_;
    const std::size_t size = size_;
    lock.unlock();
    SaveOutcome outcome;
    outcome.bytes = size;
    errno = 0;
    outcome.ok = store_->Write(name, buffer_.get(), size) == IoStatus::kOk;
    if (!outcome.ok) {
      const auto* files = dynamic_cast<const AtomicFileStore*>(store_);
      if (files != nullptr) {
        std::snprintf(outcome.error, sizeof(outcome.error), "%s", files->last_error().c_str());
      } else {
        std::snprintf(outcome.error, sizeof(outcome.error), "%s: %s", name, std::strerror(errno));
      }
    }
    lock.lock();
    outcome_ = outcome;
    saves_done_.fetch_add(1);
    state_.store(kDone, std::memory_order_release);
    wake_.notify_all();
  }
}

}  // namespace dpcr::board
