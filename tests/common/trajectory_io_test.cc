#include "common/trajectory_io.h"

#include <gtest/gtest.h>

#include <cmath>

#include "common/error.h"
#include "tests/common/test_tmpdir.h"

namespace dimer {
namespace {

TEST(TrajectoryIo, RoundTripKeepsEveryValueIncludingNaN) {
  testing::TempDir dir;
  Trajectory traj;
  for (int i = 0; i < 5; ++i) {
    traj.Append(i * 5e-4, {0.01 * i, 0.005}, {0.03 + 0.01 * i, 0.006 + i * 1e-4}, 1e-4 * i,
                0.1 * i);
  }
  traj.tip_right[2] = {NAN, NAN};
  {
    H5Writer w(dir / "t.h5");
    WriteTrajectory(w, traj);
  }
  H5Reader r(dir / "t.h5");
  Trajectory back = ReadTrajectory(r);
  ASSERT_EQ(back.size(), 5u);
  EXPECT_EQ(back.tip_left[3], traj.tip_left[3]);
  EXPECT_TRUE(std::isnan(back.tip_right[2].x()));
  EXPECT_EQ(back.theta[4], traj.theta[4]);
  EXPECT_EQ(r.AttrString("/tips/left", "units"), "m");
}

TEST(TrajectoryIo, MissingDatasetNamesFileAndDataset) {
  testing::TempDir dir;
  {
    H5Writer w(dir / "bad.h5");
    w.WriteDoubles("/t", {0.0}, {1}, "s");
  }
  H5Reader r(dir / "bad.h5");
  try {
    ReadTrajectory(r);
    FAIL();
  } catch (const InputError& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("bad.h5"), std::string::npos);
    EXPECT_NE(msg.find("/tips/left"), std::string::npos);
  }
}

}  // namespace
}  // namespace dimer
