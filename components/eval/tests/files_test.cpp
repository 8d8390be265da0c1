// Reading sequences and prediction files: valid files load, bad ones give InputError naming file and line.
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include <gtest/gtest.h>

#include "uavmot/eval/evaluate.hpp"
#include "uavmot/sim/sequence_writer.hpp"

namespace uavmot::eval {
namespace {
namespace fs = std::filesystem;

class Files : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("uavmot_eval_files_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "seq" / "gt");
    write("seq/seqinfo.ini", "[Sequence]\nname=hand\nimDir=img1\nframeRate=25\nseqLength=3\nimWidth=320\nimHeight=240\nimExt=.jpg\ngsd=0.5\n");
    write("seq/gt/gt_obb.csv",
          "frame,id,cx,cy,width,length,angle_deg,moving,parked,visibility,vx,vy\n"
          "1,1,10,10,4,10,0,1,0,1,1,0\n2,1,11,10,4,10,0,1,0,1,1,0\n3,1,12,10,4,10,0,1,0,1,1,0\n"
          "1,2,50,10,4,10,0,0,1,1,0,0\n");
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p.string();
  }
  std::string error_of(const PredictionFiles& files) {
    try {
      load_predictions(files, load_sequence((dir_ / "seq").string()).info);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
  fs::path dir_;
};

TEST_F(Files, LoadsASequenceAndScoresMotTracks) {
  const Sequence seq = load_sequence((dir_ / "seq").string());
  EXPECT_EQ(seq.info.length, 3);
  EXPECT_DOUBLE_EQ(seq.info.gsd_m, 0.5);
  ASSERT_EQ(seq.objects.at(1).size(), 2u);
  EXPECT_TRUE(seq.objects.at(1)[1].parked);
  // MOTChallenge lines: bb_left = cx - length/2 for these boxes along x.
  PredictionFiles files;
  files.tracks = write("tracks.txt", "1,7,5,8,10,4,1,-1,-1,-1\n2,7,6,8,10,4,1,-1,-1,-1\n3,7,7,8,10,4,1,-1,-1,-1\n");
  const Predictions p = load_predictions(files, seq.info);
  const EvaluationResult r = evaluate(seq, p);
  EXPECT_EQ(r.completeness.correct, 3);
  EXPECT_DOUBLE_EQ(r.tracking[0].mota, 1.0);
}

TEST_F(Files, OrientedBoxesAttachToTracksOrStandAlone) {
  const Sequence seq = load_sequence((dir_ / "seq").string());
  PredictionFiles files;
  files.oriented = write("tracks_obb.csv",
                         "frame,id,state,cx,cy,width,length,angle_deg,vx,vy\n"
                         "1,7,confirmed,10,10,4,10,0,0,0\n1,8,tentative,50,50,4,10,0,0,0\n");
  Predictions p = load_predictions(files, seq.info);
  ASSERT_EQ(p.boxes.at(1).size(), 1u);  // the tentative track is not a result
  EXPECT_TRUE(p.boxes.at(1)[0].oriented.has_value());
  files.tracks = write("tracks.txt", "1,7,5,8,10,4,1,-1,-1,-1\n");
  p = load_predictions(files, seq.info);
  ASSERT_EQ(p.boxes.at(1).size(), 1u);
  ASSERT_TRUE(p.boxes.at(1)[0].oriented.has_value());
  EXPECT_DOUBLE_EQ(p.boxes.at(1)[0].oriented->length, 10.0);
}

TEST_F(Files, MalformedTrackLinesNameFileAndLine) {
  PredictionFiles files;
  files.tracks = write("bad.txt", "1,1,5,8,10,4,1,-1,-1,-1\n2,1,five,8,10,4,1,-1,-1,-1\n");
  const std::string e = error_of(files);
  EXPECT_NE(e.find("bad.txt:2"), std::string::npos) << e;
  EXPECT_NE(e.find("five"), std::string::npos) << e;
  files.tracks = write("short.txt", "1,1,5,8\n");
  EXPECT_NE(error_of(files).find("short.txt:1"), std::string::npos);
  files.tracks = write("nan.txt", "1,1,nan,8,10,4,1,-1,-1,-1\n");
  EXPECT_NE(error_of(files).find("nan.txt:1"), std::string::npos);
  files.tracks = write("negative.txt", "1,1,5,8,-10,4,1,-1,-1,-1\n");
  EXPECT_NE(error_of(files).find("positive"), std::string::npos);
  files.tracks = write("twice.txt", "1,1,5,8,10,4,1,-1,-1,-1\n1,1,6,8,10,4,1,-1,-1,-1\n");
  EXPECT_NE(error_of(files).find("twice"), std::string::npos);
}

TEST_F(Files, FramesOutsideTheSequenceAreRejected) {
  PredictionFiles files;
  files.tracks = write("late.txt", "4,1,5,8,10,4,1,-1,-1,-1\n");
  EXPECT_NE(error_of(files).find("outside the sequence (1..3)"), std::string::npos);
  files.tracks = write("zero.txt", "0,1,5,8,10,4,1,-1,-1,-1\n");
  EXPECT_NE(error_of(files).find("zero.txt:1"), std::string::npos);
  files.tracks = write("ok.txt", "1,1,5,8,10,4,1,-1,-1,-1\n");
  files.homographies = write("h.txt", "1,1,0,0,0,1,0,0,0,1\n9,1,0,0,0,1,0,0,0,1\n");
  EXPECT_NE(error_of(files).find("h.txt:2"), std::string::npos);
  files.homographies = write("h9.txt", "2,1,0,0,0,1,0,0,0\n");
  EXPECT_NE(error_of(files).find("10 values"), std::string::npos);
  files.homographies.clear();
  files.features = write("f.csv", "frame,feature_id,x,y,vx,vy,moving\n5,1,1,1,0,0,1\n");
  EXPECT_NE(error_of(files).find("f.csv:2"), std::string::npos);
  files.features = write("g.csv", "frame,id,x,y\n1,1,1,1\n");
  EXPECT_NE(error_of(files).find("feature_id"), std::string::npos);
}

TEST_F(Files, MissingFilesAreInputErrors) {
  PredictionFiles files;
  files.tracks = (dir_ / "absent.txt").string();
  EXPECT_NE(error_of(files).find("absent.txt"), std::string::npos);
  EXPECT_THROW(load_sequence((dir_ / "nowhere").string()), InputError);
  fs::remove(dir_ / "seq" / "seqinfo.ini");
  EXPECT_THROW(load_sequence((dir_ / "seq").string()), InputError);
}

TEST_F(Files, BrokenGroundTruthIsAnInputError) {
  write("seq/gt/gt_obb.csv", "frame,id,cx,cy\n1,1,2,3\n");
  EXPECT_THROW(load_sequence((dir_ / "seq").string()), InputError);
  write("seq/seqinfo.ini", "[Sequence]\nseqLength=abc\nimWidth=320\nimHeight=240\n");
  EXPECT_THROW(load_sequence_info((dir_ / "seq" / "seqinfo.ini").string()), InputError);
}

TEST_F(Files, HugeSeqinfoNumbersAreInputErrorsNotOverflows) {
  // Found by eval_files_fuzz (tests/fuzz/regressions/eval_files/seqinfo_width_beyond_int): an
  // imWidth of 1e89 was cast to int, which is undefined behaviour.
  const std::string file = (dir_ / "seq" / "seqinfo.ini").string();
  for (const char* line : {"imWidth=1e89\nimHeight=240\nseqLength=3\n", "imWidth=320\nimHeight=3000000000\nseqLength=3\n",
                           "imWidth=320\nimHeight=240\nseqLength=1e19\n"}) {
    write("seq/seqinfo.ini", std::string("[Sequence]\n") + line);
    try {
      load_sequence_info(file);
      ADD_FAILURE() << line;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("is larger than"), std::string::npos) << e.what();
    }
  }
  write("seq/seqinfo.ini", "[Sequence]\nimWidth=1048576\nimHeight=240\nseqLength=1000000000\n");
  EXPECT_EQ(load_sequence_info(file).width, 1 << 20);
}

TEST_F(Files, SimulatedSequenceScoresPerfectlyAgainstItsOwnTruth) {
  sim::Scenario s = sim::preset_scenario("paper");
  s.frames = 4;
  s.camera.width = 320;
  s.camera.height = 240;
  s.sensor.write_video = false;
  const std::string out = (dir_ / "simseq").string();
  sim::write_sequence(s, 3, out);
  const Sequence seq = load_sequence(out);
  EXPECT_EQ(seq.info.length, 4);
  EXPECT_EQ(seq.homographies.size(), 4u);
  ASSERT_TRUE(static_cast<bool>(seq.id_mask));
  EXPECT_EQ(seq.id_mask(1).type(), CV_16U);
  // The moving objects' oriented boxes as predictions: everything correct, no false alarm.
  Predictions p;
  for (const auto& [frame, objects] : seq.objects)
    for (const auto& o : objects)
      if (o.moving) {
        PredictedBox b;
        b.id = o.id;
        b.oriented = o.box;
        b.bounds = o.bounds;
        p.boxes[frame].push_back(b);
      }
  PredictionFiles files;
  files.tracks = out + "/gt/gt.txt";  // gt.txt reads as a tracks file
  const Predictions from_file = load_predictions(files, seq.info);
  const EvaluationResult r = evaluate(seq, p);
  EXPECT_GT(r.completeness.instances, 10);
  EXPECT_EQ(r.completeness.correct, r.completeness.instances);
  EXPECT_EQ(r.false_alarms.false_alarms, 0);
  EXPECT_DOUBLE_EQ(r.tracking[0].mota, 1.0);
  EXPECT_DOUBLE_EQ(evaluate(seq, from_file).tracking[0].idf1, 1.0);
}

}  // namespace
}  // namespace uavmot::eval
