// Stands in for a GL test when the viewer is not built (GEOM_BUILD_VIEWER=OFF).
#include <gtest/gtest.h>

TEST(Gl, ViewerNotBuilt) { GTEST_SKIP() << "the viewer is not built (GEOM_BUILD_VIEWER=OFF): no GL tests"; }
