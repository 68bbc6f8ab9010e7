#pragma once
// A polymorphic value held by pointer: copying it copies the object (T::clone), so a struct
// holding one keeps value semantics without writing its copy constructor and assignment (the
// methods' options, plan entries and report parts: pipeline/method_options.hpp, method_plan.hpp,
// method_report.hpp).
#include <memory>
#include <utility>

namespace tw {

// T has `virtual std::unique_ptr<T> clone() const`; Cloneable<T, D> writes it for D.
template <class T>
class ClonePtr {
 public:
  ClonePtr() = default;
  ClonePtr(std::nullptr_t) {}
  template <class U>
  ClonePtr(std::unique_ptr<U> value) : value_(std::move(value)) {}
  ClonePtr(const ClonePtr& other) : value_(other.value_ ? other.value_->clone() : nullptr) {}
  ClonePtr& operator=(const ClonePtr& other) {
    if (this != &other) value_ = other.value_ ? other.value_->clone() : nullptr;
    return *this;
  }
  ClonePtr(ClonePtr&&) noexcept = default;
  ClonePtr& operator=(ClonePtr&&) noexcept = default;
  template <class U>
  ClonePtr& operator=(std::unique_ptr<U> value) {
    value_ = std::move(value);
    return *this;
  }

  T* get() const { return value_.get(); }
  T* operator->() const { return value_.get(); }
  T& operator*() const { return *value_; }
  explicit operator bool() const { return bool(value_); }

 private:
  std::unique_ptr<T> value_;
};

// The clone() of Derived, a Base: struct MyPlan : Cloneable<MethodPayload, MyPlan> {...}.
template <class Base, class Derived>
struct Cloneable : Base {
  std::unique_ptr<Base> clone() const override {
    return std::make_unique<Derived>(static_cast<const Derived&>(*this));
  }
};

}  // namespace tw
