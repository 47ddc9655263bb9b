// SPDX-License-Identifier: AGPL-3.0-or-later
// A bump arena for containers that allocate many blocks and free them all
// together: CGAL's Compact_container, which holds the Delaunay cells (a
// large solve's biggest memory, and before this half of its page faults:
// it grows in blocks of a few hundred KiB from the heap, on 4 KiB pages).
// Its first 64 KiB are the containers' own blocks on the heap; then chunks
// from 64 KiB, doubling up to 32 MiB, are tables (flat_vector.h): on huge
// pages (the small ones share theirs), kept warm for the next solve by the
// table cache.
//
// Containers reach it through ArenaAllocator, which takes the arena
// current on its thread when it is constructed (CGAL constructs its
// allocators itself) and never frees into it: the arena frees everything
// when it goes, so it must outlive every container that uses it (declare
// it first), and no such container may be copied or moved out of its
// scope. An arena is a local variable of one thread: arenas nest, and one
// is not shared between threads. Sanitizer builds make no arena current:
// their heap checks would not see inside a chunk.
#ifndef DOT_CORE_UTIL_BLOCK_ARENA_H_
#define DOT_CORE_UTIL_BLOCK_ARENA_H_

#include <cstddef>
#include <cstdint>
#include <new>
#include <vector>

namespace dot {

class BlockArena {
 public:
  // Becomes the current arena of this thread until it is destroyed.
  BlockArena();
  ~BlockArena();
  BlockArena(const BlockArena&) = delete;
  BlockArena& operator=(const BlockArena&) = delete;

  // `bytes` aligned for any fundamental type; throws std::bad_alloc.
  void* Allocate(size_t bytes);
  // The bytes of all chunks, used or not.
  size_t Reserved() const { return reserved_; }
  // The innermost live arena of this thread, or null.
  static BlockArena* Current();

 private:
  struct Chunk {
    char* data;
    size_t size;
  };
  std::vector<Chunk> chunks_;
  size_t used_ = 0;  // of chunks_.back()
  size_t reserved_ = 0;
  BlockArena* outer_;
};

template <typename T>
struct ArenaAllocator {
  using value_type = T;
  BlockArena* arena;

  ArenaAllocator() noexcept : arena(BlockArena::Current()) {}
  template <typename U>
  ArenaAllocator(const ArenaAllocator<U>& other) noexcept
      : arena(other.arena) {}
  T* allocate(size_t n) {
    if (n > SIZE_MAX / sizeof(T)) throw std::bad_alloc();
    if (arena == nullptr) return static_cast<T*>(::operator new(n * sizeof(T)));
    return static_cast<T*>(arena->Allocate(n * sizeof(T)));
  }
  void deallocate(T* p, size_t) noexcept {
    if (arena == nullptr) ::operator delete(p);
  }
  template <typename U>
  bool operator==(const ArenaAllocator<U>& other) const {
    return arena == other.arena;
  }
  template <typename U>
  bool operator!=(const ArenaAllocator<U>& other) const {
    return arena != other.arena;
  }
};

}  // namespace dot

#endif  // DOT_CORE_UTIL_BLOCK_ARENA_H_
