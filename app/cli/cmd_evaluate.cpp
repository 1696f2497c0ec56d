// `tactile evaluate`: cross-validate a classifier on a feature CSV and print accuracy, the
// confusion matrix, per-class figures and the misclassified segments.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "commands.h"
#include "progress.h"
#include "tactile/error.h"
#include "tactile/features/dataset.h"
#include "tactile/labels/predict.h"
#include "tactile/ml/classifier.h"
#include "tactile/ml/evaluation.h"
#include "tactile/ml/evaluation_shards.h"
#include "tactile/ml/train_all.h"
#include "tactile/skins/skin.h"

namespace tactile::cli {

namespace {

struct EvaluateArgs {
  std::string features;
  std::string classifier;
  std::string protocol = "kfold:10";
  uint64_t seed = 1;
  int threads = 0;
  bool json = false;
  bool list = false;
  std::string save_model;
  std::string out;
  std::string pipeline, pipeline_params;  // recorded in a saved model
  bool no_timings = false;
  ShardArgs shard;
};

void print_list() {
  size_t width = 0;
  for (const auto& entry : ml::classifier_catalog()) width = std::max(width, entry.name.size());
  for (const auto& entry : ml::classifier_catalog())
    std::cout << std::left << std::setw(static_cast<int>(width) + 2) << entry.name
              << entry.description << "\n";
}

std::string percent(double value) {
  std::ostringstream text;
  text << std::fixed << std::setprecision(2) << 100.0 * value << " %";
  return text.str();
}

void print_result(const ml::EvaluationResult& result, const Dataset& dataset) {
  const auto classes = static_cast<Eigen::Index>(result.classes.size());
  const int64_t correct = result.confusion.leftCols(classes).cast<int64_t>().trace();
  std::cout << "classifier  " << result.classifier << "\n"
            << "protocol    " << result.protocol << " (" << result.fold_models.size()
            << " folds, seed " << result.seed << ")\n"
            << "dataset     " << dataset.rows() << " rows, " << dataset.features.cols()
            << " features, " << classes << " classes\n"
            << "accuracy    " << std::fixed << std::setprecision(4) << result.accuracy << " ("
            << correct << "/" << result.predictions << " predictions, " << percent(result.accuracy)
            << ")\n\n";

  const bool any_unknown =
      result.confusion.cols() > classes && result.confusion.col(classes).sum() > 0;
  size_t name_width = 7;
  for (const std::string& name : result.classes) name_width = std::max(name_width, name.size());
  int cell = 6;
  for (const std::string& name : result.classes)
    cell = std::max(cell, static_cast<int>(name.size()) + 1);
  std::cout << "confusion (rows true, columns predicted)\n"
            << std::setw(static_cast<int>(name_width)) << "";
  for (const std::string& name : result.classes) std::cout << std::setw(cell) << name;
  if (any_unknown) std::cout << std::setw(cell + 2) << "unknown";
  std::cout << "\n";
  for (Eigen::Index row = 0; row < classes; ++row) {
    std::cout << std::left << std::setw(static_cast<int>(name_width))
              << result.classes[static_cast<size_t>(row)] << std::right;
    for (Eigen::Index column = 0; column < classes; ++column)
      std::cout << std::setw(cell) << result.confusion(row, column);
    if (any_unknown) std::cout << std::setw(cell + 2) << result.confusion(row, classes);
    std::cout << "\n";
  }

  std::cout << "\n"
            << std::left << std::setw(static_cast<int>(name_width)) << "class" << std::right
            << std::setw(11) << "precision" << std::setw(9) << "recall" << std::setw(9)
            << "support\n";
  for (size_t k = 0; k < result.per_class.size(); ++k) {
    const ml::ClassFigures& figure = result.per_class[k];
    std::cout << std::left << std::setw(static_cast<int>(name_width)) << result.classes[k]
              << std::right << std::setprecision(4) << std::setw(11) << figure.precision
              << std::setw(9) << figure.recall << std::setw(8) << figure.support << "\n";
  }

  // A CSV without a segment_id column reads back as id 0 on every row: name rows instead.
  std::vector<int64_t> sorted_ids = dataset.segment_ids;
  std::sort(sorted_ids.begin(), sorted_ids.end());
  const bool distinct_ids =
      static_cast<int64_t>(sorted_ids.size()) == dataset.rows() &&
      std::adjacent_find(sorted_ids.begin(), sorted_ids.end()) == sorted_ids.end();
  std::vector<int64_t> wrong_rows;
  for (const ml::Misclassified& wrong : result.misclassified) wrong_rows.push_back(wrong.row);
  std::sort(wrong_rows.begin(), wrong_rows.end());
  wrong_rows.erase(std::unique(wrong_rows.begin(), wrong_rows.end()), wrong_rows.end());
  std::cout << "\nmisclassified " << result.misclassified.size() << " predictions of "
            << wrong_rows.size() << (distinct_ids ? " segments" : " rows (no segment ids)");
  constexpr size_t kShown = 10;
  for (size_t i = 0; i < std::min(kShown, wrong_rows.size()); ++i) {
    const auto row = static_cast<size_t>(wrong_rows[i]);
    std::cout << (i == 0 ? ": " : ", ")
              << (distinct_ids ? dataset.segment_ids[row] : wrong_rows[i]);
  }
  if (wrong_rows.size() > kShown) std::cout << ", ...";
  // The tree ensembles say which columns they split on most (mean over folds).
  if (!result.importances.empty()) {
    constexpr size_t kTop = 10;
    const size_t shown = std::min(kTop, result.importances.size());
    std::cout << "\nimportance  top " << shown << " of " << result.importances.size()
              << " features used (mean over folds)\n";
    for (size_t i = 0; i < shown; ++i)
      std::cout << "  " << std::fixed << std::setprecision(4) << result.importances[i].importance
                << "  " << result.importances[i].feature << "\n";
  }
  // Grid search chooses per fold: say what it chose, and how often.
  std::map<std::string, int> chosen;
  for (const std::string& model : result.fold_models) ++chosen[model];
  if (chosen.size() > 1 || result.classifier.rfind("grid", 0) == 0)
    for (const auto& [model, folds] : chosen)
      std::cout << "\nfold model  " << model << " (" << folds << " folds)";
  std::cout << "\n"
            << std::setprecision(3) << "time        " << result.seconds << " s (fit "
            << result.fit_seconds << " s, predict " << result.predict_seconds
            << " s, summed over folds)\n";
}

// The train-all table, best first, as `--classifier all` prints it (or its JSON).
void print_all(const ml::TrainAllResult& all, const Dataset& dataset, bool json,
               const std::string& out) {
  const std::vector<ml::PresetOutcome>& outcomes = all.outcomes;
  if (json) {
    nlohmann::json table = nlohmann::json::array();
    for (const ml::PresetOutcome& outcome : outcomes) table.push_back(ml::summary_json(outcome));
    std::cout << nlohmann::json{{"protocol", all.protocol}, {"presets", table}}.dump(2) << "\n";
    return;
  }
  std::cout << "protocol " << all.protocol << ", " << dataset.rows() << " rows, "
            << dataset.features.cols() << " features, seed " << all.seed << "\n"
            << std::left << std::setw(22) << "classifier" << std::right << std::setw(10)
            << "accuracy" << std::setw(13) << "mean recall" << std::setw(10) << "time\n";
  for (const ml::PresetOutcome& outcome : outcomes) {
    std::cout << std::left << std::setw(22) << outcome.classifier << std::right;
    if (!outcome.result) {
      std::cout << "  skipped: " << outcome.skipped << "\n";
      continue;
    }
    std::cout << std::setw(10) << percent(outcome.result->accuracy) << std::setw(13)
              << percent(ml::mean_recall(*outcome.result)) << std::setw(8) << std::setprecision(2)
              << outcome.result->seconds << " s\n";
  }
  if (!out.empty()) std::cout << "results     " << out << "\n";
}

// What a single evaluation writes to --out and prints with --json.
nlohmann::json evaluation_document(const ml::EvaluationResult& result, const std::string& features,
                                   const std::string& model) {
  nlohmann::json document = ml::to_json(result, true);
  document["features"] = features;
  if (!model.empty()) document["model"] = model;
  return document;
}

// Writes what one process writes to `out` for the outcomes of a job: the train-all file, or
// the one evaluation's result.
void write_evaluation_out(const std::string& out, bool all, const ml::TrainAllResult& result) {
  if (all) {
    ml::write_train_all_file(out, result);
  } else {
    write_json_file(out, evaluation_document(*result.outcomes.front().result, result.features, ""),
                    "evaluation");
  }
}

// `--classifier all`: every preset on the same folds, a table sorted by accuracy.
void run_all(const EvaluateArgs& args, const Dataset& dataset, const ml::Protocol& protocol) {
  ProgressBar bar("evaluate all");
  ml::EvaluationControl control;
  control.threads = args.threads;
  control.scores = !args.out.empty();
  control.progress = [&](int done, int total) { bar.update(done, total); };
  ml::TrainAllResult all{protocol.to_string(), args.seed, args.features,
                         ml::evaluate_all(dataset, protocol, args.seed, control)};
  bar.finish();
  if (args.no_timings)
    for (ml::PresetOutcome& outcome : all.outcomes)
      if (outcome.result) ml::clear_timings(*outcome.result);
  ml::sort_best_first(all.outcomes);
  if (!args.out.empty()) ml::write_train_all_file(args.out, all);
  print_all(all, dataset, args.json, args.out);
}

// The job of an evaluation, as its shards and their merge see it.
ml::EvaluationJob evaluation_job(const nlohmann::json& inputs, const Dataset& dataset) {
  ml::EvaluationJob job;
  const auto classifier = inputs.at("--classifier").get<std::string>();
  job.skip_failures = classifier == "all";
  job.classifiers = {classifier};
  if (job.skip_failures) {  // the presets as one process runs them (evaluate_all)
    job.classifiers.clear();
    for (const ml::TrainAllStep& step :
         ml::train_all_plan(dataset.rows(), dataset.features.cols(),
                            static_cast<int>(dataset.class_names().size())))
      job.classifiers.push_back(step.classifier);
  }
  job.protocol = ml::Protocol::parse(inputs.at("--protocol").get<std::string>());
  job.seed = inputs.at("--seed").get<uint64_t>();
  job.scores = true;  // a shard writes --out, which holds every row's score
  return job;
}

// `--shard I/N`: this shard's folds (of every preset for `all`), kept in a part file.
void run_shard(const EvaluateArgs& args, const Dataset& dataset) {
  if (args.out.empty())
    throw Error("--shard", "needs --out (the result the merge writes; parts go beside it)");
  if (!args.save_model.empty())
    throw Error("--save-model",
                "fits on every row in one process: not with --shard (save the "
                "model with `tactile evaluate --save-model` without --shard)");
  if (args.json) throw Error("--json", "not with --shard: `tactile merge` prints the result");
  const ShardPlan plan = shard_plan(args.shard, args.out);
  Part part;
  part.command = "evaluate";
  part.shard = plan.shard;
  part.inputs = {{"--features", args.features},
                 {"features bytes", file_digest(args.features)},
                 {"--classifier", args.classifier},
                 {"--protocol", ml::Protocol::parse(args.protocol).to_string()},
                 {"--seed", args.seed},
                 {"--no-timings", args.no_timings}};
  part.result = args.out;
  const ml::EvaluationJob job = evaluation_job(part.inputs, dataset);
  const std::vector<std::string> keys = ml::evaluation_plan(dataset, job);
  part.items = static_cast<int64_t>(keys.size());
  part.plan = plan_digest(keys);
  ProgressBar bar("evaluate " + args.classifier + " shard " + plan.shard.to_string());
  ml::EvaluationControl control;
  control.threads = args.threads;
  control.progress = [&](int done, int total) { bar.update(done, total); };
  part.done = ml::run_evaluation_items(dataset, job, plan.shard, control);
  bar.finish();
  write_shard_part(plan, part);
}

void run_evaluate(const EvaluateArgs& args) {
  if (args.list) {
    print_list();
    return;
  }
  if (args.features.empty()) throw Error("--features", "required (a feature CSV)");
  if (args.classifier.empty())
    throw Error("--classifier", "required (see `tactile evaluate --list`)");
  if (args.threads < 0) throw Error("--threads", "must be 0 (all cores) or more");
  const ml::Protocol protocol = ml::Protocol::parse(args.protocol);
  const bool all = args.classifier == "all";
  if (all && !args.save_model.empty())
    throw Error("--save-model", "needs one classifier, not `all` (pick one from the table)");
  if (!all) ml::make_classifier(args.classifier);  // a bad name fails before the file is read
  if (!args.out.empty() && std::filesystem::path(args.out).extension() != ".json")
    throw Error("--out", "'" + args.out + "': the file name must end in .json");
  const Dataset dataset = read_dataset_csv(args.features);
  if (!args.shard.shard.empty() || !args.shard.part.empty()) {
    run_shard(args, dataset);
    return;
  }
  if (all) {
    run_all(args, dataset, protocol);
    return;
  }

  ProgressBar bar("evaluate " + args.classifier);
  ml::EvaluationControl control;
  control.threads = args.threads;
  control.progress = [&](int done, int total) { bar.update(done, total); };
  control.scores = !args.out.empty() || args.json;
  ml::EvaluationResult result =
      ml::evaluate(dataset, args.classifier, protocol, args.seed, control);
  bar.finish();
  if (args.no_timings) ml::clear_timings(result);
  if (!args.save_model.empty()) {
    // The skin's own pipeline unless told, when every row is of one skin.
    const std::string layout = dataset.shared_metadata("layout");
    const std::string pipeline = !args.pipeline.empty() ? args.pipeline
                                 : layout.empty()       ? ""
                                                        : default_pipeline(layout);
    write_json_file(
        args.save_model,
        fit_model_document(dataset, args.classifier, args.seed, pipeline, args.pipeline_params),
        "model");
  }
  if (!args.out.empty())
    write_json_file(args.out, evaluation_document(result, args.features, args.save_model),
                    "evaluation");
  if (args.json) {
    std::cout << evaluation_document(result, args.features, args.save_model).dump(2) << "\n";
  } else {
    print_result(result, dataset);
    if (!args.save_model.empty())
      std::cout << "model       " << args.save_model << " (fitted on all rows)\n";
    if (!args.out.empty()) std::cout << "result      " << args.out << "\n";
  }
}

}  // namespace

void merge_evaluate(const std::vector<Part>& parts, const std::string& out) {
  const nlohmann::json& inputs = parts.front().inputs;
  const auto features = inputs.at("--features").get<std::string>();
  const Dataset dataset = read_dataset_csv(features);
  if (file_digest(features) != inputs.at("features bytes"))
    throw Error(features, "changed since the shards read it; run them again");
  const ml::EvaluationJob job = evaluation_job(inputs, dataset);
  ml::TrainAllResult result{job.protocol.to_string(), job.seed, features,
                            ml::outcomes_from_items(dataset, job, items_in_order(parts))};
  if (inputs.at("--no-timings").get<bool>())
    for (ml::PresetOutcome& outcome : result.outcomes)
      if (outcome.result) ml::clear_timings(*outcome.result);
  const bool all = job.skip_failures;
  if (all) ml::sort_best_first(result.outcomes);
  write_evaluation_out(out, all, result);
  if (all)
    print_all(result, dataset, false, out);
  else {
    print_result(*result.outcomes.front().result, dataset);
    std::cout << "result      " << out << "\n";
  }
}

void register_evaluate(CLI::App& app) {
  auto args = std::make_shared<EvaluateArgs>();
  CLI::App* command = app.add_subcommand(
      "evaluate", "Cross-validate a classifier on a feature CSV (accuracy, confusion, errors)");
  command->add_option("--features", args->features,
                      "Feature CSV (from `tactile features`, or any CSV with a class column)");
  command->add_option("--classifier", args->classifier,
                      "NAME[:key=value,...], e.g. knn:k=3,metric=cosine (see --list); "
                      "`all`: every preset, a table sorted by accuracy");
  command->add_option("--out", args->out,
                      "Write the result as JSON (confusion, per-class figures and every test "
                      "row: recording, t0, t1, region, true, predicted, score)");
  command
      ->add_option(
          "--protocol", args->protocol,
          "kfold:K[xR] | loo | loso | group:COLUMN | holdout:FxR | split:TRAIN_QUERY/TEST_QUERY")
      ->capture_default_str();
  command->add_option("--seed", args->seed, "Random seed of folds and classifiers")
      ->capture_default_str();
  command->add_option("--threads", args->threads, "Worker threads (0: every core)")
      ->capture_default_str();
  command->add_option("--save-model", args->save_model,
                      "Also fit on every row and save the model as JSON");
  command->add_option("--pipeline", args->pipeline,
                      "With --save-model: the feature pipeline that made the table (default: "
                      "the skin's own, from the rows' layout)");
  command->add_option("--pipeline-params", args->pipeline_params,
                      "With --save-model: that pipeline's --params");
  command->add_flag("--json", args->json, "Print the result as JSON");
  command->add_flag("--no-timings", args->no_timings,
                    "Write 0 for every time, so that the same inputs give the same bytes (a "
                    "result to compare, or one merged from shards)");
  add_shard_options(command, args->shard);
  command->add_flag("--list", args->list, "List the classifier names and exit");
  command->callback([args] { run_evaluate(*args); });
}

}  // namespace tactile::cli
