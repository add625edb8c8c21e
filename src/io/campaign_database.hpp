#pragma once
// A campaign's results in SQLite (DIR/campaign.sqlite): one row per finished run, each written in
// its own transaction (WAL journal), so that killing the campaign at any moment loses at most the
// runs in flight. Written by one thread of one process (the coordinator); docs/campaigns.md has the
// schema.
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

struct sqlite3;

namespace biped {

struct CampaignRow {
  long run = 0;
  std::string status;         // ok | error
  std::string error;          // the message, for status error
  nlohmann::json parameters = nlohmann::json::object();  // varied key -> value (number or text)
  std::string command;        // reproduces the run
  nlohmann::json result = nlohmann::json::object();      // the run's summary (timings removed)
  double wall_time_s = 0.0;
  std::string host;
  int rank = 0;
};

// The columns drawn from a run's summary (JSON pointer into `result`), in the table and results.csv.
struct ResultColumn {
  const char* name;
  const char* pointer;
  const char* type;  // SQL: INTEGER, REAL or TEXT
};
const std::vector<ResultColumn>& campaign_result_columns();

class CampaignDatabase {
 public:
  // Opens (creating when absent) the database file; throws InputError naming it when it cannot.
  explicit CampaignDatabase(const std::string& path);
  ~CampaignDatabase();
  CampaignDatabase(const CampaignDatabase&) = delete;
  CampaignDatabase& operator=(const CampaignDatabase&) = delete;

  // Binds the database to one campaign: stores `identity` and `total` the first time; afterwards
  // throws InputError when they differ (another campaign's results are never mixed in).
  void claim(const std::string& identity, long total);
  std::set<long> finished_runs() const;
  void insert(const CampaignRow& row);  // one transaction
  std::vector<CampaignRow> rows() const;  // by run index
  const std::string& path() const { return path_; }

 private:
  void execute(const std::string& sql) const;
  std::string meta(const std::string& key) const;
  sqlite3* db_ = nullptr;
  std::string path_;
};

}  // namespace biped
