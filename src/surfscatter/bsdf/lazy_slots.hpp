#pragma once
// A fixed number of slots whose values are built on first use and then read without a lock: the per-wavelength
// GHS tables and the per-g sampling proposals are looked up on every eval / pdf, where a shared_mutex and a map
// cost more than the interpolation itself. Two threads may build the same slot at once; one result is kept.
#include <atomic>
#include <cstddef>
#include <memory>
#include <mutex>
#include <vector>

namespace surfscatter::bsdf {

template <class T>
class LazySlots {
public:
    explicit LazySlots(std::size_t count) : count_(count), slots_(new std::atomic<const T*>[count]()) {}
    LazySlots(const LazySlots&) = delete;
    LazySlots& operator=(const LazySlots&) = delete;

    std::size_t size() const { return count_; }

    // The value of slot i (< size()), made by build() the first time.
    template <class Build>
    const T& get(std::size_t i, Build&& build) const {
        if (const T* t = slots_[i].load(std::memory_order_acquire)) return *t;
        return make(i, build);
    }

private:
    template <class Build>
    [[gnu::noinline]] const T& make(std::size_t i, Build& build) const {  // keeps get() small enough to inline
        auto made = std::make_unique<const T>(build());
        std::lock_guard lock(mutex_);
        if (const T* t = slots_[i].load(std::memory_order_acquire)) return *t;
        slots_[i].store(made.get(), std::memory_order_release);
        owned_.push_back(std::move(made));
        return *owned_.back();
    }

    std::size_t count_;
    std::unique_ptr<std::atomic<const T*>[]> slots_;
    mutable std::mutex mutex_;
    mutable std::vector<std::unique_ptr<const T>> owned_;
};

}  // namespace surfscatter::bsdf
