// ClonePtr (core/clone_ptr.hpp): a struct holding one copies its object, so two copies never
// share it; moving hands it over; null stays null. The methods' options, plan entries and
// report parts rely on this for their value semantics.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "core/clone_ptr.hpp"

namespace tw {
namespace {

struct Shape {
  virtual ~Shape() = default;
  virtual std::unique_ptr<Shape> clone() const = 0;
  virtual int corners() const = 0;
};

struct Square : Cloneable<Shape, Square> {
  std::vector<int> sides = {1, 1, 1, 1};
  int corners() const override { return 4; }
};

// Aggregates, as the pipeline's parts are.
struct Named {
  int id = 0;
  ClonePtr<Shape> shape;
};

TEST(ClonePtr, ACopyHoldsItsOwnObjectOfTheSameDynamicType) {
  Named a{1, std::make_unique<Square>()};
  Named b = a;
  ASSERT_TRUE(b.shape);
  EXPECT_NE(b.shape.get(), a.shape.get());
  EXPECT_EQ(b.shape->corners(), 4);
  auto* square = dynamic_cast<Square*>(b.shape.get());
  ASSERT_NE(square, nullptr);
  square->sides[0] = 7;  // the original is not touched
  EXPECT_EQ(static_cast<const Square&>(*a.shape).sides[0], 1);

  Named c;
  c = a;  // assignment copies too
  EXPECT_NE(c.shape.get(), a.shape.get());
  c = c;  // and survives itself
  EXPECT_TRUE(c.shape);
}

TEST(ClonePtr, MovingHandsTheObjectOverAndNullCopiesAsNull) {
  Named a{1, std::make_unique<Square>()};
  const Shape* held = a.shape.get();
  Named b = std::move(a);
  EXPECT_EQ(b.shape.get(), held);
  Named empty;
  Named copy = empty;
  EXPECT_FALSE(copy.shape);
  std::vector<Named> parts;
  parts.emplace_back(2, std::make_unique<Square>());  // as the pipeline adds a part
  EXPECT_EQ(parts.back().id, 2);
  EXPECT_EQ(parts.back().shape->corners(), 4);
}

}  // namespace
}  // namespace tw
