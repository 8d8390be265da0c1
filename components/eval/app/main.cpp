// uavmot-eval: scores a run (tracks, homographies, features; from result files or a recording)
// against a simulated sequence.
#include <fstream>
#include <iostream>
#include <string>

#include "uavmot/core/app.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/eval/evaluate.hpp"
#include "recorded_predictions.hpp"

namespace uavmot {
namespace {

int eval_main(int argc, char** argv) {
  std::string seq_dir, json_file, recording, stream_id;
  eval::PredictionFiles files;
  eval::EvalOptions options;
  return run_app(argc, argv, "eval",
                 "score tracks, homographies and features against ground truth (paper Tables I/II, CLEAR MOT, IDF1, HOTA)",
                 [&](CLI::App& app) -> AppBody {
    app.add_option("--seq", seq_dir, "MOTChallenge sequence folder with gt/ (from uavmot sim)");
    app.add_option("--pred", files.tracks, "tracks in MOTChallenge format: frame,id,bb_left,bb_top,bb_width,bb_height,conf,-1,-1,-1");
    app.add_option("--obb", files.oriented, "oriented boxes (tracks_obb.csv: frame,id,[state,]cx,cy,width,length,angle_deg,...)");
    app.add_option("--homographies", files.homographies, "estimated homographies: frame,h11..h33");
    app.add_option("--features", files.features, "classified features: frame,feature_id,x,y,vx,vy,moving (with header)");
    auto* from_recording =
        app.add_option("--recording", recording,
                       "score a recorded run (uavmot record): the tracks on uavmot/tracks and the homographies and "
                       "features on uavmot/motion, instead of files");
    app.add_option("--stream-id", stream_id, "with --recording: the stream to score (default: the only one)")->needs(from_recording);
    for (auto* files_option : {app.get_option("--pred"), app.get_option("--obb"), app.get_option("--homographies"),
                               app.get_option("--features")}) {
      files_option->excludes(from_recording);
    }
    app.add_option("--json", json_file, "also write the results as JSON to this file");
    app.add_option("--min-visibility", options.min_visibility, "moving objects less visible than this are not scored")->check(uavmot::finite_range(0.0, 1.0));
    app.add_option("--min-object-coverage", options.min_object_coverage,
                   "Table I: a box belongs to an object when it covers at least this share of the object area")->check(uavmot::finite_range(0.01, 1.0));
    app.add_option("--min-box-on-object", options.min_box_on_object,
                   "Table I: ... or when at least this share of the box lies on the object")->check(uavmot::finite_range(0.01, 1.0));
    app.add_option("--feature-tolerance", options.feature_tolerance_px,
                   "features within this distance (px) of a moving object's pixels but not on them are ambiguous, not scored")
        ->check(uavmot::non_negative_finite())
        ->capture_default_str();
    app.add_option("--first-frame", options.first_frame, "first frame to score")->check(uavmot::non_negative_finite());
    app.add_option("--last-frame", options.last_frame, "last frame to score")->check(uavmot::non_negative_finite());
    return [&]() -> int {
      if (seq_dir.empty()) throw InputError("give --seq DIR");
      if (recording.empty() && files.tracks.empty() && files.oriented.empty()) {
        throw InputError("give --pred tracks.txt (or --obb tracks_obb.csv, or --recording run.mcap)");
      }
      const eval::Sequence sequence = eval::load_sequence(seq_dir);
      const eval::Predictions predictions = recording.empty()
                                                ? eval::load_predictions(files, sequence.info)
                                                : eval::load_recorded_predictions(recording, stream_id, sequence.info);
      const eval::EvaluationResult result = eval::evaluate(sequence, predictions, options);
      std::cout << eval::format_table(result);
      if (!json_file.empty()) {
        std::ofstream out(json_file);
        out << eval::to_json(result).dump(2) << "\n";
        if (!out) throw InputError("cannot write '" + json_file + "'");
      }
      return kExitOk;
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::eval_main(argc, argv); }
