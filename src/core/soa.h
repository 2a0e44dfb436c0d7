// Structure-of-arrays storage. A queue's fields are listed once, as an X-macro in
// queue_fields.h; ERPT_SOA_STRUCT turns that list into a struct with one aligned column per
// field plus resize()/size(). Kernels take columns (or the whole struct) and an index range.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <utility>
#include <vector>

#include "erpt/math.h"

namespace erpt {

// Memory for a column: 64-byte aligned (a cache line; SIMD loads align). Columns of several
// megabytes (seed stores, vertex histories) are placed on 2 MB boundaries and offered to the
// kernel as transparent huge pages: touched afresh in 4 KB pages, their page faults took a
// tenth of an ERPT render (docs/performance.md). Where the kernel declines, nothing changes.
void* allocateColumn(size_t bytes);

template <class T>
struct AlignedAllocator {
  using value_type = T;
  AlignedAllocator() = default;
  template <class U>
  AlignedAllocator(const AlignedAllocator<U>&) {}
  T* allocate(size_t n) { return static_cast<T*>(allocateColumn(n * sizeof(T))); }
  void deallocate(T* p, size_t) { std::free(p); }
  // A column grown without a value leaves its new elements default-initialised (for the
  // scalars in columns: unwritten), so that resizeForOverwrite costs no pass over the memory;
  // resize() passes the zero explicitly.
  template <class U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  template <class U>
  bool operator==(const AlignedAllocator<U>&) const { return true; }
  template <class U>
  bool operator!=(const AlignedAllocator<U>&) const { return false; }
};

template <class T>
using Column = std::vector<T, AlignedAllocator<T>>;

struct IndexRange {
  size_t begin = 0, end = 0;
  size_t size() const { return end - begin; }
};

}  // namespace erpt

// Columns: one per scalar field, three per vector (X, Y, Z) and colour (R, G, B) field.
#define ERPT_SOA_COLUMN(type, name, init, doc) ::erpt::Column<type> name;
#define ERPT_SOA_VEC_COLUMNS(name, doc) ::erpt::Column<float> name##X, name##Y, name##Z;
#define ERPT_SOA_COLOR_COLUMNS(name, doc) ::erpt::Column<float> name##R, name##G, name##B;
#define ERPT_SOA_RESIZE(type, name, init, doc) name.resize(n, type{});
#define ERPT_SOA_VEC_RESIZE(name, doc) name##X.resize(n, 0.0f), name##Y.resize(n, 0.0f), name##Z.resize(n, 0.0f);
#define ERPT_SOA_COLOR_RESIZE(name, doc) name##R.resize(n, 0.0f), name##G.resize(n, 0.0f), name##B.resize(n, 0.0f);
#define ERPT_SOA_GROW(type, name, init, doc) name.resize(n);
#define ERPT_SOA_RESERVE(type, name, init, doc) name.reserve(n);
#define ERPT_SOA_VEC_RESERVE(name, doc) name##X.reserve(n), name##Y.reserve(n), name##Z.reserve(n);
#define ERPT_SOA_COLOR_RESERVE(name, doc) name##R.reserve(n), name##G.reserve(n), name##B.reserve(n);
#define ERPT_SOA_VEC_GROW(name, doc) name##X.resize(n), name##Y.resize(n), name##Z.resize(n);
#define ERPT_SOA_COLOR_GROW(name, doc) name##R.resize(n), name##G.resize(n), name##B.resize(n);
#define ERPT_SOA_COPY_ROW(type, name, init, doc) name[to] = from.name[at];
#define ERPT_SOA_VEC_COPY_ROW(name, doc) \
  name##X[to] = from.name##X[at], name##Y[to] = from.name##Y[at], name##Z[to] = from.name##Z[at];
#define ERPT_SOA_COLOR_COPY_ROW(name, doc) \
  name##R[to] = from.name##R[at], name##G[to] = from.name##G[at], name##B[to] = from.name##B[at];
// The Row type: one member per field, with the field's default.
#define ERPT_SOA_ROW_MEMBER(type, name, init, doc) type name = init;
#define ERPT_SOA_VEC_ROW_MEMBER(name, doc) ::erpt::Vec3 name;
#define ERPT_SOA_COLOR_ROW_MEMBER(name, doc) ::erpt::Color name;
#define ERPT_SOA_LOAD(type, name, init, doc) r.name = name[i];
#define ERPT_SOA_VEC_LOAD(name, doc) r.name = ::erpt::Vec3(name##X[i], name##Y[i], name##Z[i]);
#define ERPT_SOA_COLOR_LOAD(name, doc) r.name = ::erpt::Color(name##R[i], name##G[i], name##B[i]);
#define ERPT_SOA_STORE(type, name, init, doc) name[i] = r.name;
#define ERPT_SOA_VEC_STORE(name, doc) name##X[i] = r.name.x, name##Y[i] = r.name.y, name##Z[i] = r.name.z;
#define ERPT_SOA_COLOR_STORE(name, doc) name##R[i] = r.name.x, name##G[i] = r.name.y, name##B[i] = r.name.z;
// nameAt(i) / nameSet(i, value) for vector and colour fields; nothing for scalars.
#define ERPT_SOA_NO_ACCESSOR(type, name, init, doc)
#define ERPT_SOA_VEC_ACCESSORS(name, doc)                                                           \
  ::erpt::Vec3 name##At(size_t i) const { return ::erpt::Vec3(name##X[i], name##Y[i], name##Z[i]); } \
  void name##Set(size_t i, ::erpt::Vec3 v) { name##X[i] = v.x, name##Y[i] = v.y, name##Z[i] = v.z; }
#define ERPT_SOA_COLOR_ACCESSORS(name, doc)                                                            \
  ::erpt::Color name##At(size_t i) const { return ::erpt::Color(name##R[i], name##G[i], name##B[i]); } \
  void name##Set(size_t i, ::erpt::Color c) { name##R[i] = c.x, name##G[i] = c.y, name##B[i] = c.z; }

#define ERPT_SOA_STRUCT(Name, FIELDS)                                                          \
  struct Name {                                                                                \
    FIELDS(ERPT_SOA_COLUMN, ERPT_SOA_VEC_COLUMNS, ERPT_SOA_COLOR_COLUMNS)                      \
    size_t count = 0;                                                                          \
    struct Row {                                                                               \
      FIELDS(ERPT_SOA_ROW_MEMBER, ERPT_SOA_VEC_ROW_MEMBER, ERPT_SOA_COLOR_ROW_MEMBER)          \
    };                                                                                         \
    /* new rows are zero */                                                                    \
    void resize(size_t n) {                                                                    \
      FIELDS(ERPT_SOA_RESIZE, ERPT_SOA_VEC_RESIZE, ERPT_SOA_COLOR_RESIZE)                      \
      count = n;                                                                               \
    }                                                                                          \
    /* new rows are unwritten: for a stage that writes every row before any is read (a */      \
    /* serial zeroing pass, and its page faults, cost a tenth of an ERPT render on 2 threads) */ \
    void resizeForOverwrite(size_t n) {                                                        \
      FIELDS(ERPT_SOA_GROW, ERPT_SOA_VEC_GROW, ERPT_SOA_COLOR_GROW)                            \
      count = n;                                                                               \
    }                                                                                          \
    /* room for n rows (address space: pages are touched by whoever writes them first) */     \
    void reserve(size_t n) { FIELDS(ERPT_SOA_RESERVE, ERPT_SOA_VEC_RESERVE, ERPT_SOA_COLOR_RESERVE) } \
    size_t size() const { return count; }                                                      \
    /* row `to` of this = row `at` of `from` */                                                \
    void copyRow(size_t to, const Name& from, size_t at) {                                     \
      FIELDS(ERPT_SOA_COPY_ROW, ERPT_SOA_VEC_COPY_ROW, ERPT_SOA_COLOR_COPY_ROW)                \
    }                                                                                          \
    Row row(size_t i) const {                                                                  \
      Row r;                                                                                   \
      FIELDS(ERPT_SOA_LOAD, ERPT_SOA_VEC_LOAD, ERPT_SOA_COLOR_LOAD)                            \
      return r;                                                                                \
    }                                                                                          \
    void setRow(size_t i, const Row& r) { FIELDS(ERPT_SOA_STORE, ERPT_SOA_VEC_STORE, ERPT_SOA_COLOR_STORE) } \
    FIELDS(ERPT_SOA_NO_ACCESSOR, ERPT_SOA_VEC_ACCESSORS, ERPT_SOA_COLOR_ACCESSORS)             \
  };

// A view: a value type over some of a queue's fields (a sub-list of its X-macro), with
// loadView(queue, i) and storeView(queue, i, value) that touch only those columns.
#define ERPT_SOA_Q_LOAD(type, name, init, doc) r.name = q.name[i];
#define ERPT_SOA_Q_VEC_LOAD(name, doc) r.name = ::erpt::Vec3(q.name##X[i], q.name##Y[i], q.name##Z[i]);
#define ERPT_SOA_Q_COLOR_LOAD(name, doc) r.name = ::erpt::Color(q.name##R[i], q.name##G[i], q.name##B[i]);
#define ERPT_SOA_Q_STORE(type, name, init, doc) q.name[i] = r.name;
#define ERPT_SOA_Q_VEC_STORE(name, doc) q.name##X[i] = r.name.x, q.name##Y[i] = r.name.y, q.name##Z[i] = r.name.z;
#define ERPT_SOA_Q_COLOR_STORE(name, doc) q.name##R[i] = r.name.x, q.name##G[i] = r.name.y, q.name##B[i] = r.name.z;
#define ERPT_SOA_VIEW(View, Queue, FIELDS)                                                 \
  struct View {                                                                            \
    FIELDS(ERPT_SOA_ROW_MEMBER, ERPT_SOA_VEC_ROW_MEMBER, ERPT_SOA_COLOR_ROW_MEMBER)        \
  };                                                                                       \
  /* into `r` in place: hot loops filling arrays of views avoid a temporary whose fields */ \
  /* were just stored one by one and are then copied with wide loads (a store-forwarding */ \
  /* stall that cost the accept stage ~20%) */                                             \
  inline void load##View(const Queue& q, size_t i, View& r) {                              \
    FIELDS(ERPT_SOA_Q_LOAD, ERPT_SOA_Q_VEC_LOAD, ERPT_SOA_Q_COLOR_LOAD)                    \
  }                                                                                        \
  inline View load##View(const Queue& q, size_t i) {                                       \
    View r;                                                                                \
    load##View(q, i, r);                                                                   \
    return r;                                                                              \
  }                                                                                        \
  inline void store##View(Queue& q, size_t i, const View& r) {                             \
    FIELDS(ERPT_SOA_Q_STORE, ERPT_SOA_Q_VEC_STORE, ERPT_SOA_Q_COLOR_STORE)                 \
  }
