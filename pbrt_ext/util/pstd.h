// pbrt_ext: device-usable stand-ins for std::optional and std::span (pbrt-v4's util/pstd.h).
// The standard ones are not callable from CUDA device code, and std::optional::value() throws.
#pragma once

#include "pbrt_ext/pbrt.h"

#include <cassert>
#include <cstddef>
#include <iterator>
#include <new>
#include <type_traits>
#include <utility>

namespace pstd {

// optional<T>: value() on an empty optional is a precondition violation (asserted), never a throw.
template <typename T>
class optional {
  public:
    using value_type = T;

    // The union leaves `val` unconstructed until a value arrives, so T needs no default constructor.
    PBRT_CPU_GPU optional() {}
    PBRT_CPU_GPU optional(const T &v) { emplace(v); }
    PBRT_CPU_GPU optional(T &&v) { emplace(std::move(v)); }
    PBRT_CPU_GPU optional(const optional &other) { *this = other; }
    PBRT_CPU_GPU optional(optional &&other) { *this = std::move(other); }
    PBRT_CPU_GPU ~optional() { reset(); }

    PBRT_CPU_GPU optional &operator=(const optional &other) {
        if (this != &other) {
            reset();
            if (other.set) emplace(other.val);
        }
        return *this;
    }
    PBRT_CPU_GPU optional &operator=(optional &&other) {
        if (this != &other) {
            reset();
            if (other.set) emplace(std::move(other.val));
        }
        return *this;
    }
    PBRT_CPU_GPU optional &operator=(const T &v) {
        emplace(v);
        return *this;
    }
    PBRT_CPU_GPU optional &operator=(T &&v) {
        emplace(std::move(v));
        return *this;
    }

    template <typename... Args>
    PBRT_CPU_GPU T &emplace(Args &&...args) {
        reset();
        new (&val) T(std::forward<Args>(args)...);
        set = true;
        return val;
    }
    PBRT_CPU_GPU void reset() {
        if (set) val.~T();
        set = false;
    }

    PBRT_CPU_GPU bool has_value() const { return set; }
    PBRT_CPU_GPU explicit operator bool() const { return set; }

    PBRT_CPU_GPU T &value() {
        assert(set);
        return val;
    }
    PBRT_CPU_GPU const T &value() const {
        assert(set);
        return val;
    }
    template <typename U>
    PBRT_CPU_GPU T value_or(U &&alternative) const {
        return set ? val : static_cast<T>(std::forward<U>(alternative));
    }

    PBRT_CPU_GPU T &operator*() { return value(); }
    PBRT_CPU_GPU const T &operator*() const { return value(); }
    PBRT_CPU_GPU T *operator->() { return &value(); }
    PBRT_CPU_GPU const T *operator->() const { return &value(); }

  private:
    union {
        T val;
    };
    bool set = false;
};

template <typename T>
class span;

namespace detail {
template <typename T>
inline constexpr bool IsSpan = false;
template <typename T>
inline constexpr bool IsSpan<span<T>> = true;
}  // namespace detail

// span<T>: a non-owning view of contiguous elements.
template <typename T>
class span {
  public:
    using element_type = T;
    using value_type = std::remove_cv_t<T>;
    using size_type = std::size_t;
    using iterator = T *;
    static constexpr size_type npos = static_cast<size_type>(-1);

    span() = default;
    PBRT_CPU_GPU constexpr span(T *data, size_type size) : ptr(data), n(size) {}
    template <size_type N>
    PBRT_CPU_GPU constexpr span(T (&array)[N]) : ptr(array), n(N) {}
    // span<T> -> span<const T>, as std::span allows.
    template <typename U>
        requires std::is_convertible_v<U (*)[], T (*)[]>
    PBRT_CPU_GPU constexpr span(span<U> other) : ptr(other.data()), n(other.size()) {}
    // Host-only: std::vector, std::array and the like are not device types.
    template <typename Container>
        requires(!detail::IsSpan<std::remove_cvref_t<Container>> &&
                 !std::is_array_v<std::remove_reference_t<Container>> &&
                 std::is_convertible_v<decltype(std::data(std::declval<Container &>())), T *>)
    span(Container &&c) : ptr(std::data(c)), n(std::size(c)) {}

    PBRT_CPU_GPU constexpr T *data() const { return ptr; }
    PBRT_CPU_GPU constexpr size_type size() const { return n; }
    PBRT_CPU_GPU constexpr bool empty() const { return n == 0; }
    PBRT_CPU_GPU constexpr T &operator[](size_type i) const {
        assert(i < n);
        return ptr[i];
    }
    PBRT_CPU_GPU constexpr T &front() const { return (*this)[0]; }
    PBRT_CPU_GPU constexpr T &back() const { return (*this)[n - 1]; }
    PBRT_CPU_GPU constexpr iterator begin() const { return ptr; }
    PBRT_CPU_GPU constexpr iterator end() const { return ptr + n; }

    // Like std::span::subspan, but a count running past the end is clipped instead of undefined.
    PBRT_CPU_GPU constexpr span subspan(size_type pos, size_type count = npos) const {
        assert(pos <= n);
        return span(ptr + pos, count < n - pos ? count : n - pos);
    }

  private:
    T *ptr = nullptr;
    size_type n = 0;
};

}  // namespace pstd
