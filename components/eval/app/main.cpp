// uavmot-eval: scores a run (tracks, homographies, features) against a simulated sequence.
#include <fstream>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "uavmot/core/error.hpp"
#include "uavmot/eval/evaluate.hpp"

int main(int argc, char** argv) {
  constexpr const char* kDescription = "score tracks, homographies and features against ground truth (paper Tables I/II, CLEAR MOT, IDF1, HOTA)";
  CLI::App app{std::string("uavmot-eval: ") + kDescription};
  bool describe = false;
  std::string seq_dir, json_file;
  uavmot::eval::PredictionFiles files;
  uavmot::eval::EvalOptions options;
  app.add_flag("--describe", describe, "print one line describing this command and exit");
  app.add_option("--seq", seq_dir, "MOTChallenge sequence folder with gt/ (from uavmot sim)");
  app.add_option("--pred", files.tracks, "tracks in MOTChallenge format: frame,id,bb_left,bb_top,bb_width,bb_height,conf,-1,-1,-1");
  app.add_option("--obb", files.oriented, "oriented boxes (tracks_obb.csv: frame,id,[state,]cx,cy,width,length,angle_deg,...)");
  app.add_option("--homographies", files.homographies, "estimated homographies: frame,h11..h33");
  app.add_option("--features", files.features, "classified features: frame,feature_id,x,y,vx,vy,moving (with header)");
  app.add_option("--json", json_file, "also write the results as JSON to this file");
  app.add_option("--min-visibility", options.min_visibility, "moving objects less visible than this are not scored")->check(CLI::Range(0.0, 1.0));
  app.add_option("--min-object-coverage", options.min_object_coverage,
                 "Table I: a box belongs to an object when it covers at least this share of the object area")->check(CLI::Range(0.01, 1.0));
  app.add_option("--min-box-on-object", options.min_box_on_object,
                 "Table I: ... or when at least this share of the box lies on the object")->check(CLI::Range(0.01, 1.0));
  app.add_option("--first-frame", options.first_frame, "first frame to score")->check(CLI::NonNegativeNumber);
  app.add_option("--last-frame", options.last_frame, "last frame to score")->check(CLI::NonNegativeNumber);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  if (describe) {
    std::cout << kDescription << "\n";
    return 0;
  }
  try {
    if (seq_dir.empty()) throw uavmot::InputError("give --seq DIR");
    if (files.tracks.empty() && files.oriented.empty()) throw uavmot::InputError("give --pred tracks.txt (or --obb tracks_obb.csv)");
    const uavmot::eval::Sequence sequence = uavmot::eval::load_sequence(seq_dir);
    const uavmot::eval::Predictions predictions = uavmot::eval::load_predictions(files, sequence.info);
    const uavmot::eval::EvaluationResult result = uavmot::eval::evaluate(sequence, predictions, options);
    std::cout << uavmot::eval::format_table(result);
    if (!json_file.empty()) {
      std::ofstream out(json_file);
      out << uavmot::eval::to_json(result).dump(2) << "\n";
      if (!out) throw uavmot::InputError("cannot write '" + json_file + "'");
    }
    return 0;
  } catch (const uavmot::InputError& e) {
    std::cerr << "uavmot-eval: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "uavmot-eval: error: " << e.what() << "\n";
    return 1;
  }
}
