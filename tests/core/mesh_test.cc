#include <gtest/gtest.h>
#include "core/mesh.h"
TEST(Mesh, Placeholder) { SUCCEED(); }
