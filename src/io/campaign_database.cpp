#include "io/campaign_database.hpp"

#include <sqlite3.h>

#include <memory>
#include <stdexcept>

#include "io/yaml_reader.hpp"

namespace biped {
namespace {

// A prepared statement, finalized on scope exit.
class Statement {
 public:
  Statement(sqlite3* db, const std::string& sql) : db_(db) {
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &stmt_, nullptr) != SQLITE_OK) {
      throw std::runtime_error(std::string("SQLite: ") + sqlite3_errmsg(db) + " in: " + sql);
    }
  }
  ~Statement() { sqlite3_finalize(stmt_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  void bind(int i, const std::string& text) { check(sqlite3_bind_text(stmt_, i, text.c_str(), -1, SQLITE_TRANSIENT)); }
  void bind(int i, double value) { check(sqlite3_bind_double(stmt_, i, value)); }
  void bind(int i, long value) { check(sqlite3_bind_int64(stmt_, i, value)); }
  void bind_null(int i) { check(sqlite3_bind_null(stmt_, i)); }
  void bind_json(int i, const nlohmann::json& v, bool text) {
    if (v.is_null()) return bind_null(i);
    if (text) return bind(i, v.is_string() ? v.get<std::string>() : v.dump());
    if (v.is_boolean()) return bind(i, static_cast<long>(v.get<bool>()));
    if (v.is_number()) return bind(i, v.get<double>());
    bind(i, v.dump());
  }
  bool step() {
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    throw std::runtime_error(std::string("SQLite: ") + sqlite3_errmsg(db_));
  }
  std::string text(int column) const {
    const unsigned char* t = sqlite3_column_text(stmt_, column);
    return t ? reinterpret_cast<const char*>(t) : "";
  }
  double number(int column) const { return sqlite3_column_double(stmt_, column); }
  long integer(int column) const { return static_cast<long>(sqlite3_column_int64(stmt_, column)); }

 private:
  void check(int rc) const {
    if (rc != SQLITE_OK) throw std::runtime_error(std::string("SQLite: ") + sqlite3_errmsg(db_));
  }
  sqlite3* db_;
  sqlite3_stmt* stmt_ = nullptr;
};

}  // namespace

const std::vector<ResultColumn>& campaign_result_columns() {
  static const std::vector<ResultColumn> columns = {
      {"fell", "/fell", "INTEGER"},
      {"fall_time_s", "/fall_time_s", "REAL"},
      {"fall_reason", "/fall_reason", "TEXT"},
      {"distance_m", "/distance_m", "REAL"},
      {"commanded_speed_mps", "/commanded_speed_mps", "REAL"},
      {"achieved_speed_mps", "/mean_speed_mps", "REAL"},
      {"tilt_max_deg", "/upper_body_tilt_deg/max", "REAL"},
      {"tilt_rms_x_deg", "/upper_body_tilt_deg/rms_x", "REAL"},
      {"tilt_rms_y_deg", "/upper_body_tilt_deg/rms_y", "REAL"},
      {"fault", "/fault", "TEXT"},
      {"sim_time_s", "/sim_time_s", "REAL"},
      {"expected", "/expected", "TEXT"},
      {"as_expected", "/as_expected", "INTEGER"},
  };
  return columns;
}

CampaignDatabase::CampaignDatabase(const std::string& path) : path_(path) {
  if (sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) != SQLITE_OK) {
    const std::string message = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    throw InputError(path + ": cannot open the campaign database: " + message);
  }
  sqlite3_busy_timeout(db_, 10000);
  try {
    // WAL: a commit is one append; a process killed mid-write leaves the last commit intact.
    execute("PRAGMA journal_mode=WAL");
    execute("PRAGMA synchronous=NORMAL");
    std::string columns;
    for (const ResultColumn& c : campaign_result_columns()) columns += std::string(", ") + c.name + " " + c.type;
    execute("CREATE TABLE IF NOT EXISTS meta (key TEXT PRIMARY KEY, value TEXT NOT NULL)");
    execute("CREATE TABLE IF NOT EXISTS runs (run INTEGER PRIMARY KEY, status TEXT NOT NULL, error TEXT, "
            "parameters TEXT NOT NULL" + columns + ", wall_time_s REAL, host TEXT, rank INTEGER, command TEXT, "
            "result TEXT)");
    execute("CREATE TABLE IF NOT EXISTS run_parameters (run INTEGER NOT NULL, key TEXT NOT NULL, value TEXT, "
            "number REAL, PRIMARY KEY (run, key))");
  } catch (const std::runtime_error& e) {
    sqlite3_close(db_);
    throw InputError(path + ": not a campaign database: " + e.what());
  }
  // A database an older biped wrote has other columns: continuing it would fail at the first insert.
  std::string missing;
  for (const ResultColumn& c : campaign_result_columns()) {
    Statement s(db_, "SELECT count(*) FROM pragma_table_info('runs') WHERE name = ?");
    s.bind(1, std::string(c.name));
    if (s.step() && s.integer(0) == 0) missing += missing.empty() ? c.name : std::string(", ") + c.name;
  }
  if (!missing.empty()) {
    sqlite3_close(db_);
    throw InputError(path + ": written by another version of biped (no column " + missing +
                     "); use another --out or remove the folder");
  }
}

CampaignDatabase::~CampaignDatabase() { sqlite3_close(db_); }

void CampaignDatabase::execute(const std::string& sql) const {
  char* message = nullptr;
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &message) != SQLITE_OK) {
    const std::string text = message ? message : "unknown error";
    sqlite3_free(message);
    throw std::runtime_error("SQLite: " + text + " in: " + sql);
  }
}

std::string CampaignDatabase::meta(const std::string& key) const {
  Statement s(db_, "SELECT value FROM meta WHERE key = ?");
  s.bind(1, key);
  return s.step() ? s.text(0) : "";
}

void CampaignDatabase::claim(const std::string& identity, long total) {
  const std::string stored = meta("identity");
  if (stored.empty()) {
    execute("BEGIN");
    for (const auto& [key, value] : {std::pair<std::string, std::string>{"identity", identity}, {"runs", std::to_string(total)}}) {
      Statement s(db_, "INSERT OR REPLACE INTO meta (key, value) VALUES (?, ?)");
      s.bind(1, key);
      s.bind(2, value);
      s.step();
    }
    execute("COMMIT");
    return;
  }
  if (stored != identity || meta("runs") != std::to_string(total)) {
    throw InputError(path_ + ": holds the results of another campaign (a different campaign file, --set, or base "
                             "scenario); use another --out or remove the folder");
  }
}

std::set<long> CampaignDatabase::finished_runs() const {
  std::set<long> runs;
  Statement s(db_, "SELECT run FROM runs");
  while (s.step()) runs.insert(s.integer(0));
  return runs;
}

void CampaignDatabase::insert(const CampaignRow& row) {
  const auto& columns = campaign_result_columns();
  std::string names = "run, status, error, parameters, wall_time_s, host, rank, command, result", marks = "?, ?, ?, ?, ?, ?, ?, ?, ?";
  for (const ResultColumn& c : columns) {
    names += std::string(", ") + c.name;
    marks += ", ?";
  }
  execute("BEGIN");
  try {
    Statement s(db_, "INSERT INTO runs (" + names + ") VALUES (" + marks + ")");
    s.bind(1, row.run);
    s.bind(2, row.status);
    if (row.error.empty()) s.bind_null(3); else s.bind(3, row.error);
    s.bind(4, row.parameters.dump());
    s.bind(5, row.wall_time_s);
    s.bind(6, row.host);
    s.bind(7, static_cast<long>(row.rank));
    s.bind(8, row.command);
    s.bind(9, row.result.dump());
    for (std::size_t i = 0; i < columns.size(); ++i) {
      const nlohmann::json::json_pointer pointer(columns[i].pointer);
      s.bind_json(static_cast<int>(10 + i), row.result.contains(pointer) ? row.result[pointer] : nlohmann::json(), columns[i].type == std::string("TEXT"));
    }
    s.step();
    for (const auto& [key, value] : row.parameters.items()) {
      Statement p(db_, "INSERT INTO run_parameters (run, key, value, number) VALUES (?, ?, ?, ?)");
      p.bind(1, row.run);
      p.bind(2, key);
      p.bind(3, value.is_string() ? value.get<std::string>() : value.dump());
      if (value.is_number()) p.bind(4, value.get<double>()); else p.bind_null(4);
      p.step();
    }
    execute("COMMIT");
  } catch (...) {
    execute("ROLLBACK");
    throw;
  }
}

std::vector<CampaignRow> CampaignDatabase::rows() const {
  std::vector<CampaignRow> rows;
  Statement s(db_, "SELECT run, status, error, parameters, command, result, wall_time_s, host, rank FROM runs ORDER BY run");
  while (s.step()) {
    CampaignRow row;
    row.run = s.integer(0);
    row.status = s.text(1);
    row.error = s.text(2);
    row.parameters = nlohmann::json::parse(s.text(3));
    row.command = s.text(4);
    row.result = nlohmann::json::parse(s.text(5));
    row.wall_time_s = s.number(6);
    row.host = s.text(7);
    row.rank = static_cast<int>(s.integer(8));
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace biped
