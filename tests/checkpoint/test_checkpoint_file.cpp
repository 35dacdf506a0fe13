// The checkpoint file (checkpoint/checkpoint_file.hpp): every column type round-trips bit for bit,
// and a file that is truncated, altered, of another version or read in another order is refused
// with a message naming it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "checkpoint/checkpoint_file.hpp"
#include "numerics/grid.hpp"
#include "physics/unsaturated_state.hpp"
#include "physics/voigt.hpp"

namespace unsatmpm {
namespace test_checkpoint_file {

namespace fs = std::filesystem;

class CheckpointFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("unsatmpm_ckpt_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    file_ = dir_ / "checkpoint.bin";
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// A checkpoint of a few sections of every kind.
  void write_sample() {
    CheckpointWriter w(file_, "sample");
    w.text("case", "name: x\n");
    w.put("doubles", doubles_);
    w.put("ids", std::vector<std::int64_t>{0, -1, std::numeric_limits<std::int64_t>::max()});
    w.put("materials", std::vector<int>{3, 1});
    w.put("flags", std::vector<std::uint8_t>{1, 0, 1});
    w.put("positions", std::vector<numerics::Vec<3>>{{1, 2, 3}, {-4, 5e-300, 6}});
    w.put("stress", std::vector<physics::Vec6>{physics::Vec6::Constant(-2.5)});
    w.put("storage", std::vector<physics::StorageMatrix>{{1, 2, 3, 4}});
    w.put("empty", std::vector<double>{});
    w.value("time", 0.1 + 0.2);
    w.finish();
  }

  std::vector<char> bytes() const {
    std::ifstream in(file_, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  void set_bytes(const std::vector<char>& b) const {
    std::ofstream out(file_, std::ios::binary | std::ios::trunc);
    out.write(b.data(), static_cast<std::streamsize>(b.size()));
  }

  /// Reads the sample back completely; throws what the reader throws.
  void read_sample() const {
    CheckpointReader r(file_);
    r.text("case");
    std::vector<double> d;
    r.get("doubles", d);
    std::vector<std::int64_t> ids;
    r.get("ids", ids);
    std::vector<int> materials;
    r.get("materials", materials);
    std::vector<std::uint8_t> flags;
    r.get("flags", flags);
    std::vector<numerics::Vec<3>> x;
    r.get("positions", x);
    std::vector<physics::Vec6> stress;
    r.get("stress", stress);
    std::vector<physics::StorageMatrix> storage;
    r.get("storage", storage);
    r.get("empty", d);
    r.value<double>("time");
    r.finish();
  }

  std::string error_of(const std::function<void()>& f) const {
    try {
      f();
    } catch (const CheckpointError& e) {
      return e.what();
    }
    return "";
  }

  fs::path dir_, file_;
  std::vector<double> doubles_{1.0 / 3.0, -0.0, std::numeric_limits<double>::denorm_min(),
                               std::numeric_limits<double>::infinity(), 6.02e23};
};

TEST_F(CheckpointFileTest, EveryColumnTypeRoundTripsBitForBit) {
  write_sample();
  CheckpointReader r(file_);
  EXPECT_EQ(r.text("case"), "name: x\n");
  std::vector<double> d;
  r.get("doubles", d);
  ASSERT_EQ(d.size(), doubles_.size());
  EXPECT_EQ(std::memcmp(d.data(), doubles_.data(), d.size() * sizeof(double)), 0);
  std::vector<std::int64_t> ids;
  r.get("ids", ids);
  EXPECT_EQ(ids, (std::vector<std::int64_t>{0, -1, std::numeric_limits<std::int64_t>::max()}));
  std::vector<int> materials;
  r.get_sized("materials", materials, 2);
  EXPECT_EQ(materials, (std::vector<int>{3, 1}));
  std::vector<std::uint8_t> flags;
  r.get("flags", flags);
  EXPECT_EQ(flags, (std::vector<std::uint8_t>{1, 0, 1}));
  std::vector<numerics::Vec<3>> x;
  r.get("positions", x);
  ASSERT_EQ(x.size(), 2u);
  EXPECT_EQ(x[1], numerics::Vec<3>(-4, 5e-300, 6));
  std::vector<physics::Vec6> stress;
  r.get("stress", stress);
  EXPECT_EQ(stress.at(0), physics::Vec6::Constant(-2.5));
  std::vector<physics::StorageMatrix> storage;
  r.get("storage", storage);
  EXPECT_EQ(storage.at(0).gl, 3.0);
  r.get("empty", d);
  EXPECT_TRUE(d.empty());
  EXPECT_EQ(r.value<double>("time"), 0.1 + 0.2);
  EXPECT_NO_THROW(r.finish());
}

TEST_F(CheckpointFileTest, ReadingInAnotherOrderNamesBothSections) {
  write_sample();
  CheckpointReader r(file_);
  const std::string e = error_of([&] { r.text("cycle"); });
  EXPECT_NE(e.find("expected section 'cycle', found 'case'"), std::string::npos) << e;
  EXPECT_NE(e.find(file_.string()), std::string::npos) << e;
}

TEST_F(CheckpointFileTest, ReadingAsAnotherTypeIsRefused) {
  write_sample();
  CheckpointReader r(file_);
  r.text("case");
  std::vector<numerics::Vec<2>> wrong;  // the doubles are 1 component wide, not 2
  const std::string e = error_of([&] { r.get("doubles", wrong); });
  EXPECT_NE(e.find("f64 x 1, expected f64 x 2"), std::string::npos) << e;
}

TEST_F(CheckpointFileTest, AColumnOfAnotherSizeIsRefused) {
  write_sample();
  CheckpointReader r(file_);
  r.text("case");
  std::vector<double> d;
  const std::string e = error_of([&] { r.get_sized("doubles", d, 7); });
  EXPECT_NE(e.find("holds 5 elements where the case has 7"), std::string::npos) << e;
}

TEST_F(CheckpointFileTest, ATruncatedFileIsRefusedAtOnce) {
  write_sample();
  auto b = bytes();
  for (const std::size_t keep : {b.size() - 1, b.size() / 2, std::size_t{30}, std::size_t{3}}) {
    set_bytes(std::vector<char>(b.begin(), b.begin() + static_cast<std::ptrdiff_t>(keep)));
    const std::string e = error_of([&] { CheckpointReader r(file_); });
    EXPECT_FALSE(e.empty()) << "kept " << keep << " bytes";
  }
}

TEST_F(CheckpointFileTest, AnAlteredByteFailsTheHash) {
  write_sample();
  auto b = bytes();
  // A bit of one of the doubles' values: the layout is intact, the contents are not.
  const double value = 6.02e23;
  const auto at = std::search(b.begin(), b.end(), reinterpret_cast<const char*>(&value),
                              reinterpret_cast<const char*>(&value) + sizeof value);
  ASSERT_NE(at, b.end());
  *at ^= 0x01;
  set_bytes(b);
  const std::string e = error_of([&] { read_sample(); });
  EXPECT_NE(e.find("do not match their hash"), std::string::npos) << e;
}

TEST_F(CheckpointFileTest, AnotherFormatVersionIsRefusedWithItsNumber) {
  write_sample();
  auto b = bytes();
  const std::uint32_t other = checkpoint_format_version + 1;
  std::memcpy(b.data() + 16, &other, 4);
  set_bytes(b);
  const std::string e = error_of([&] { CheckpointReader r(file_); });
  EXPECT_NE(e.find("checkpoint format version " + std::to_string(other)), std::string::npos) << e;
  EXPECT_NE(e.find("run the case again"), std::string::npos) << e;
}

TEST_F(CheckpointFileTest, AFileThatIsNoCheckpointIsRefused) {
  { std::ofstream(file_) << "name: a case file, not a checkpoint, long enough to pass the size\n"; }
  EXPECT_NE(error_of([&] { CheckpointReader r(file_); }).find("not a checkpoint"),
            std::string::npos);
  fs::remove(file_);
  EXPECT_NE(error_of([&] { CheckpointReader r(file_); }).find("cannot open"), std::string::npos);
}

TEST_F(CheckpointFileTest, SectionsLeftUnreadAreReported) {
  write_sample();
  CheckpointReader r(file_);
  r.text("case");
  EXPECT_NE(error_of([&] { r.finish(); }).find("left unread"), std::string::npos);
}

TEST_F(CheckpointFileTest, AWriteThatCannotHappenNamesTheFileAndTheReason) {
  try {
    CheckpointWriter w(dir_ / "no_such_folder" / "checkpoint.bin", "'the checkpoint'");
    FAIL() << "opened a file in a missing folder";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot write 'the checkpoint': No such file"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace test_checkpoint_file
}  // namespace unsatmpm
