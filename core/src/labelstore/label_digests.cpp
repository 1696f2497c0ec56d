// The digests of label_rows.h: per scope the number of rows and the sum of their hashes.
#include <nlohmann/json.hpp>

#include "label_rows.h"
#include "row_checksum.h"
#include "tactile/error.h"
#include "tactile/text.h"

namespace tactile::label_rows {

using row_checksum::Field;

//---- Digests

namespace {

std::vector<Field> digest_fields(const std::string& scope, int64_t rows, uint64_t sum) {
  return {{"scope", scope}, {"rows", rows}, {"sum", static_cast<int64_t>(sum)}};
}

}  // namespace

void adjust_digest(sqlite3* database, const std::string& path, const std::string& scope,
                   int64_t rows, uint64_t sum) {
  Digest digest;
  {
    sqlite::Statement select(database, path,
                             "SELECT rows, sum, checksum FROM digests WHERE scope = ?");
    select.bind(1, scope);
    if (select.step()) {
      digest.rows = select.integer(0);
      digest.sum = static_cast<uint64_t>(select.integer(1));
      if (const auto problem = checksum_problem(
              "digests", 0, digest_fields(scope, digest.rows, digest.sum), select.text(2)))
        throw Error(path + " digest of " + scope,
                    problem->what + "; run tactile verify, nothing was written");
    }
  }
  digest.rows += rows;
  digest.sum += sum;  // modulo 2^64
  sqlite::Statement upsert(database, path,
                           "INSERT OR REPLACE INTO digests (scope, rows, sum, checksum) "
                           "VALUES (?, ?, ?, ?)");
  upsert.bind(1, scope)
      .bind(2, digest.rows)
      .bind(3, static_cast<int64_t>(digest.sum))
      .bind(4, row_checksum::compute("digests", 0, digest_fields(scope, digest.rows, digest.sum)));
  upsert.run();
}

std::map<std::string, Digest> read_digests(sqlite3* database, const std::string& prefix,
                                           std::vector<StoreProblem>& problems) {
  sqlite::Statement select(database, "",
                           "SELECT scope, rows, sum, checksum FROM digests WHERE "
                           "substr(scope, 1, length(?1)) = ?1");
  select.bind(1, prefix);
  std::map<std::string, Digest> digests;
  while (select.step()) {
    const std::string scope = select.text(0);
    Digest digest{select.integer(1), static_cast<uint64_t>(select.integer(2))};
    if (auto problem = checksum_problem("digests", 0, digest_fields(scope, digest.rows, digest.sum),
                                        select.text(3))) {
      problem->field = scope;
      problems.push_back(*problem);
      continue;
    }
    digests[scope] = digest;
  }
  return digests;
}

void compare_digests(const std::map<std::string, Digest>& found,
                     const std::map<std::string, Digest>& stored, bool all_scopes,
                     std::vector<StoreProblem>& problems) {
  auto compare = [&problems](const std::string& scope, const Digest& seen, const Digest& kept) {
    if (seen.rows == kept.rows && seen.sum == kept.sum) return;
    problems.push_back(StoreProblem{"digests", 0, scope,
                                    std::to_string(seen.rows) + " rows read, " +
                                        std::to_string(kept.rows) + " written" +
                                        (seen.rows == kept.rows ? " (the rows differ)" : "") +
                                        ": rows lost, added or changed on disk"});
  };
  for (const auto& [scope, seen] : found) {
    const auto kept = stored.find(scope);
    compare(scope, seen, kept == stored.end() ? Digest{} : kept->second);
  }
  if (!all_scopes) return;
  for (const auto& [scope, kept] : stored)
    if (found.count(scope) == 0) compare(scope, Digest{}, kept);
}

}  // namespace tactile::label_rows
