// bake/src/aggregate_fields.h — the number of members of an aggregate, at compile time: the
// largest n for which T{x₁, …, xₙ} compiles with xᵢ convertible to anything. Counts top-level
// members (a nested struct is one member); used to make a static_assert fail when an options
// struct gains a member that a serialiser does not list.
#pragma once

#include <cstddef>

namespace prt::bake::detail {

struct AnyMember {
  template <class T>
  operator T() const;  // declared only: used in unevaluated contexts
};

template <class T, class... Given>
constexpr std::size_t aggregate_member_count() {
  if constexpr (requires { T{Given{}..., AnyMember{}}; })
    return aggregate_member_count<T, Given..., AnyMember>();
  else
    return sizeof...(Given);
}

}  // namespace prt::bake::detail
