#include "board/map_store.hpp"

namespace dpcr::board {

IoStatus ReadBlob(BlobStore& store, const char* name, std::uint64_t max_bytes, std::vector<std::uint8_t>* out) {
  out->clear();
  std::uint8_t chunk[16384];
  for (;;) {
    const ByteRead r = store.ReadAt(name, out->size(), chunk, sizeof(chunk));
    if (r.status != IoStatus::kOk) return r.status;
    if (r.size == 0) return IoStatus::kOk;
    out->insert(out->end(), chunk, chunk + r.size);
    if (out->size() > max_bytes) return IoStatus::kOk;  // already larger than any map: the loader refuses it
  }
}

}  // namespace dpcr::board
