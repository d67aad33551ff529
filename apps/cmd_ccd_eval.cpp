// `weft ccd-eval <dir>`: runs the CCD narrow phase on every benchmark query file below dir and scores it
// against the files' ground truth.
#include "apps/cli.hpp"
#include "backends/ccd_batch.hpp"
#include "collision/ccd_query_file.hpp"

#include <iostream>
#include <stdexcept>

namespace weft::cli {

namespace {

struct CcdEvalOptions {
  std::string dir;
  real ms = 0;
  CcdSettings settings;
};

void add_ccd_eval(CLI::App& app, const GlobalOptions& g, Action& run) {
  static CcdEvalOptions o;
  auto* cmd = app.add_subcommand("ccd-eval", "score the CCD narrow phase on benchmark query files (*.csv below dir)");
  cmd->add_option("dir", o.dir, "folder searched recursively for query files")->required();
  cmd->add_option("--ms", o.ms, "minimum separation (default 0)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--tolerance", o.settings.tolerance, "CCD tolerance (default 1e-6)")->check(CLI::PositiveNumber);
  cmd->add_option("--max-iterations", o.settings.max_iterations, "boxes per query before a conservative hit")
      ->check(CLI::PositiveNumber);
  cmd->callback([&g, &run] {
    run = [&g] {
      const Backend b = resolve_backend(g);
      std::vector<CcdQueryFile> files;
      try {
        for (const auto& path : find_ccd_query_files(o.dir)) files.push_back(read_ccd_query_file(path));
      } catch (const std::runtime_error& e) {
        throw Error(e.what(), 2);
      }
      if (files.empty()) throw Error(o.dir + ": no *.csv query files", 2);
      Runtime rt(g.threads);
      long queries = 0, false_negatives = 0, false_positives = 0;
      for (const auto& f : files) {
        const auto results = ccd_batch(b, f.kind, f.rows, o.ms, o.settings);
        queries += f.size();
        std::cout << f.path << " queries " << f.size();
        if (f.truth.empty()) {
          long hits = 0;
          for (const auto& r : results) hits += r.hit;
          std::cout << " hits " << hits << " (no truth: not scored)\n";
          continue;
        }
        long fn = 0, fp = 0;
        for (long q = 0; q < f.size(); ++q) {
          fn += f.truth[q] && !results[q].hit;
          fp += !f.truth[q] && results[q].hit;
        }
        false_negatives += fn;
        false_positives += fp;
        std::cout << " false-negatives " << fn << " false-positives " << fp << "\n";
      }
      std::cout << "queries " << queries << " false-negatives " << false_negatives << " false-positives "
                << false_positives << "\n";
      return false_negatives == 0 ? 0 : 1;
    };
  });
}

const Register reg("ccd-eval", add_ccd_eval);

}  // namespace
}  // namespace weft::cli
