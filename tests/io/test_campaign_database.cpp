// The campaign database (io/campaign_database.cpp): rows written and read back whole, the finished
// runs, a database bound to one campaign, and rows surviving a reopen.
#include "io/campaign_database.hpp"

#include <gtest/gtest.h>
#include <sqlite3.h>

#include "io/yaml_reader.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

CampaignRow row(long run, bool fell) {
  CampaignRow r;
  r.run = run;
  r.status = "ok";
  r.parameters = {{"commands.1.vx", 0.25}, {"sensors.noise", "true"}};
  r.command = "build/biped run x.yaml --set seed=" + std::to_string(run);
  r.result = {{"fell", fell}, {"fall_time_s", fell ? nlohmann::json(3.5) : nlohmann::json(nullptr)},
              {"distance_m", 1.5}, {"upper_body_tilt_deg", {{"max", 2.0}, {"rms_x", 0.5}, {"rms_y", 0.4}}}};
  r.wall_time_s = 0.5;
  r.host = "node1";
  r.rank = 1;
  return r;
}

TEST(CampaignDatabase, RowsReadBackWholeInRunOrder) {
  const auto path = (test::fresh_dir("db-rows") / "c.sqlite").string();
  CampaignDatabase db(path);
  db.claim("campaign A", 3);
  db.insert(row(2, true));
  db.insert(row(0, false));
  CampaignRow error;
  error.run = 1;
  error.status = "error";
  error.error = "it threw";
  db.insert(error);
  EXPECT_EQ(db.finished_runs(), (std::set<long>{0, 1, 2}));
  const std::vector<CampaignRow> rows = db.rows();
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].run, 0);
  EXPECT_EQ(rows[1].error, "it threw");
  EXPECT_EQ(rows[2].result, row(2, true).result);
  EXPECT_EQ(rows[2].parameters, row(2, true).parameters);
  EXPECT_EQ(rows[2].command, row(2, true).command);
  EXPECT_EQ(rows[2].host, "node1");
  EXPECT_EQ(rows[2].rank, 1);
}

TEST(CampaignDatabase, RowsSurviveAReopen) {
  const auto path = (test::fresh_dir("db-reopen") / "c.sqlite").string();
  {
    CampaignDatabase db(path);
    db.claim("campaign A", 5);
    db.insert(row(4, false));
  }
  CampaignDatabase again(path);
  again.claim("campaign A", 5);
  EXPECT_EQ(again.finished_runs(), std::set<long>{4});
}

TEST(CampaignDatabase, RefusesAnotherCampaignsResults) {
  const auto path = (test::fresh_dir("db-claim") / "c.sqlite").string();
  CampaignDatabase db(path);
  db.claim("campaign A", 5);
  EXPECT_THROW(db.claim("campaign B", 5), InputError);
  EXPECT_THROW(db.claim("campaign A", 6), InputError);
}

TEST(CampaignDatabase, ARunIsStoredOnce) {
  const auto path = (test::fresh_dir("db-once") / "c.sqlite").string();
  CampaignDatabase db(path);
  db.insert(row(1, false));
  EXPECT_ANY_THROW(db.insert(row(1, true)));
  EXPECT_EQ(db.rows().size(), 1u);
}

TEST(CampaignDatabase, RefusesADatabaseWithOtherColumns) {
  const auto path = (test::fresh_dir("db-schema") / "c.sqlite").string();
  sqlite3* raw = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &raw), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(raw, "CREATE TABLE runs (run INTEGER PRIMARY KEY, status TEXT NOT NULL, error TEXT, "
                              "parameters TEXT NOT NULL, fell INTEGER, wall_time_s REAL, host TEXT, rank INTEGER, "
                              "command TEXT, result TEXT)",
                         nullptr, nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(raw);
  try {
    CampaignDatabase db(path);
    FAIL() << "an older database was opened";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("fall_time_s"), std::string::npos) << e.what();
  }
}

TEST(CampaignDatabase, UnwritablePlaceIsBadInput) {
  EXPECT_THROW(CampaignDatabase("/nonexistent-folder/c.sqlite"), InputError);
}

}  // namespace
}  // namespace biped
