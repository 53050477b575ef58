// The config keys through the program: `--set` of repose / sweep keys reports the key the user
// typed, `config-keys` regenerates docs/config.md's tables, and the repose resolved config lists
// every key of the schema.

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "aggpack/config/docs.h"
#include "support/cli_test.h"

namespace aggpack {
namespace {

using test::CliRun;

class ConfigCli : public test::CliTest {
 public:
  ConfigCli() : CliTest("aggpack_config_cli_") {}
};

#ifdef AGGPACK_HAS_SIM
// The example: before the schema this reported `repose.baffle_speed` (an options field)
// through a rename table; now the reader names the key as typed.
TEST_F(ConfigCli, ReposeSetNamesTheKeyTheUserTyped) {
  for (const char* command : {"repose", "sweep"}) {
    const CliRun run = this->run(std::string(command) + " --set trough.baffle_speed=-1 -o out");
    EXPECT_EQ(run.exit_code, 2) << run.err;
    EXPECT_EQ(run.err,
              "aggpack: error: --set trough.baffle_speed=-1: invalid trough.baffle_speed = -1 "
              "(allowed: (0, 1e6] m/s)\n");
    EXPECT_TRUE(files().empty()) << "an output folder was left";
  }
  // A rule only the options' validator knows (the baffle inside the trough) names the key too.
  const CliRun inside = run("repose --set trough.baffle_position=7 --print-config");
  EXPECT_EQ(inside.exit_code, 2);
  EXPECT_NE(inside.err.find("invalid trough.baffle_position = 7"), std::string::npos) << inside.err;
  EXPECT_EQ(inside.err.find("repose."), std::string::npos) << inside.err;
  // A typo gets a suggestion from the same schema.
  const CliRun typo = run("repose --set physics.frictoin=0.3 --print-config");
  EXPECT_EQ(typo.exit_code, 2);
  EXPECT_NE(typo.err.find("did you mean 'physics.friction'?"), std::string::npos) << typo.err;
}

TEST_F(ConfigCli, ReposePrintConfigAppliesSetAndFlags) {
  const CliRun run = this->run(
      "repose --set physics.wall_friction=0.3 --set 'sweep.alphas=[0.5]' --mu 0.4 "
      "--print-config");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("\nfriction = 0.4  # "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("\nwall_friction = 0.3  # "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("\nalphas = [0.5]  # "), std::string::npos) << run.out;
}
#endif

TEST_F(ConfigCli, ConfigKeysUpdatesTheDocTables) {
  const std::string doc =
      "# keys\n<!-- generated: aggpack config-keys --markdown packer -->\nold\n"
      "<!-- end generated -->\n";
  { std::ofstream(path("config.md")) << doc; }
  const CliRun update = run("config-keys --update-doc config.md");
  ASSERT_EQ(update.exit_code, 0) << update.err;
  EXPECT_EQ(test::file_text(path("config.md")), regenerate_config_doc(doc));
  EXPECT_EQ(run("config-keys --update-doc config.md").out, "config.md is up to date\n");
  const CliRun list = run("config-keys");
  ASSERT_EQ(list.exit_code, 0) << list.err;
  EXPECT_NE(list.out.find("packer.gap  float (m)  default `0.0`  allowed [0, 1e6]"),
            std::string::npos)
      << list.out;
  EXPECT_EQ(run("config-keys --markdown nonsense").exit_code, 2);
}

}  // namespace
}  // namespace aggpack
