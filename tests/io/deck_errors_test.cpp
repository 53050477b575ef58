// --deck: names, format choice, deterministic output, and bad options: each gives a one-line
// error naming the option and leaves no file behind; the CLI end to end.

#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"
#include "aggpack/io/export.h"
#include "aggpack/io/native.h"
#include "deck_fixture.h"
#include "support/paths.h"

namespace aggpack {
namespace {

using test::ScratchFolder;

TEST(DeckChoice, NamesAndFormats) {
  for (DeckKind kind : {DeckKind::kNone, DeckKind::kAbaqus, DeckKind::kCalculix, DeckKind::kLsDyna,
                        DeckKind::kYade}) {
    EXPECT_EQ(parse_deck_kind(deck_name(kind)), kind);
  }
  EXPECT_EQ(parse_deck_kind("CCX"), DeckKind::kCalculix);
  EXPECT_EQ(parse_deck_kind("LS-DYNA"), DeckKind::kLsDyna);
  EXPECT_THROW(parse_deck_kind("ansys"), InvalidInput);
  ExportOptions options;
  options.deck.kind = DeckKind::kCalculix;
  EXPECT_EQ(resolve_format("deck.inp", options), ExportFormat::kAbaqus);
  EXPECT_EQ(resolve_format("deck", options), ExportFormat::kAbaqus);  // no extension: the deck's
  options.deck.kind = DeckKind::kYade;
  EXPECT_EQ(resolve_format("deck.py", options), ExportFormat::kYade);
  EXPECT_THROW(resolve_format("deck.inp", options), InvalidInput);  // another format's extension
}

TEST(DeckOptionsCheck, BadOptionsNameTheOptionAndLeaveNoFile) {
  const Packing packing = test::pile_near_floor(2, 1, 1, 0.01);
  ScratchFolder folder;
  auto field_of = [&](const std::string& name, ExportOptions options) {
    if (options.deck.kind == DeckKind::kNone) options.deck.kind = DeckKind::kCalculix;
    try {
      write(packing, folder.file(name), options);
    } catch (const InvalidInput& error) {
      return error.field();
    }
    return std::string("no error");
  };
  const auto deck = [](DeckOptions d) { return ExportOptions{.deck = d}; };
  const DeckKind ccx = DeckKind::kCalculix;
  EXPECT_EQ(field_of("a.inp", deck({.kind = ccx, .friction = -0.1})), "friction");
  EXPECT_EQ(field_of("a.inp", deck({.kind = ccx, .friction = 11})), "friction");
  EXPECT_EQ(field_of("a.inp", deck({.kind = ccx, .gravity = 0})), "gravity");
  EXPECT_EQ(field_of("a.inp", deck({.kind = ccx, .baffle_speed = 0})), "baffle speed");
  EXPECT_EQ(field_of("a.inp", deck({.kind = ccx, .settle_time = -1})), "settle time");
  EXPECT_EQ(field_of("a.inp", deck({.kind = ccx, .rest_time = NAN})), "rest time");
  EXPECT_EQ(field_of("a.inp", deck({.kind = ccx, .contact_distance = -1})), "contact distance");
  EXPECT_EQ(field_of("a.py", deck({.kind = DeckKind::kYade, .time_step = -1})), "time step");
  // Geometry: the baffle must stand beyond the particles, the trough end beyond the baffle.
  EXPECT_EQ(field_of("a.inp", deck({.kind = ccx, .baffle_position = 0.2})), "baffle position");
  EXPECT_EQ(field_of("a.inp", deck({.kind = ccx, .trough_length = 0.3})), "trough length");
  // Combinations a deck cannot hold.
  EXPECT_EQ(field_of("a.k", deck({.kind = ccx})), "output extension");
  ExportOptions parts = deck({.kind = ccx});
  parts.abaqus_layout = AbaqusLayout::kPartsInstances;
  EXPECT_EQ(field_of("a.inp", parts), "inp layout");
  ExportOptions quadratic = deck({.kind = DeckKind::kAbaqus});
  quadratic.is_quadratic = true;
  EXPECT_EQ(field_of("a.inp", quadratic), "quadratic");
  quadratic.deck.kind = DeckKind::kCalculix;  // ccx has C3D10
  EXPECT_EQ(field_of("a.inp", quadratic), "no error");
  EXPECT_EQ(field_of("empty.inp", ExportOptions{.deck = {.kind = ccx}}), "no error");
  EXPECT_EQ(folder.entries(), (std::vector<std::string>{"a.inp", "empty.inp"}));
  Packing empty = packing;
  empty.particles.clear();
  EXPECT_THROW(write(empty, folder.file("none.inp"), deck({.kind = ccx})), InvalidInput);
  EXPECT_EQ(folder.entries().size(), 2U);  // no temporary file left
}

TEST(DeckOutput, SameBytesForAnyThreadCountAndDefaultsFromTheContainer) {
  const Packing packing = test::grid_packing(3, 2, 2, 7);
  ScratchFolder folder;
  for (DeckKind kind :
       {DeckKind::kAbaqus, DeckKind::kCalculix, DeckKind::kLsDyna, DeckKind::kYade}) {
    const ExportOptions options{.deck = {.kind = kind}};
    const std::string name = deck_name(kind) + "." + format_name(resolve_format("x", options));
    write(packing, folder.file("n" + name), options);
    {
      const ThreadLimit one(1);
      write(packing, folder.file("1" + name), options);
    }
    const std::string text = test::read_text(folder.file("1" + name));
    EXPECT_EQ(text, test::read_text(folder.file("n" + name))) << name;
    // Defaults: baffle at the container's end (x = 1.05), trough twice as long, step times.
    EXPECT_NE(text.find("x = 1.05 across the trough"), std::string::npos) << name;
    EXPECT_NE(text.find("Trough: x 0 .. 2.1,"), std::string::npos) << name;
    EXPECT_NE(text.find("Step BAFFLE, 2.1 s"), std::string::npos) << name;
  }
}

TEST(DeckCli, ExportDeckEndToEnd) {
  const Packing packing = test::pile_near_floor(2, 1, 1, 0.01);
  ScratchFolder folder;
  write_packing(packing, folder.file("p.h5"));
  const std::string binary = test::aggpack_binary();
  auto result = test::run_command(binary + " export " + folder.file("p.h5") +
                                  " --deck calculix --friction 0.3 --settle-time 0.2 -o " +
                                  folder.file("trough.inp"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("wrote"), std::string::npos);
  const std::string text = test::read_text(folder.file("trough.inp"));
  EXPECT_NE(text.find("*FRICTION\n0.3,"), std::string::npos);
  EXPECT_NE(text.find("Step SETTLE, 0.2 s"), std::string::npos);
  result = test::run_command(binary + " export " + folder.file("p.h5") +
                             " --deck lsdyna --friction 12 -o " + folder.file("t.k"));
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("friction = 12"), std::string::npos) << result.output;
  result = test::run_command(binary + " export " + folder.file("p.h5") + " --deck nastran -o " +
                             folder.file("t.k"));
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("deck"), std::string::npos) << result.output;
  EXPECT_EQ(folder.entries(), (std::vector<std::string>{"p.h5", "trough.inp"}));
}

}  // namespace
}  // namespace aggpack
