#pragma once
// The library's errors and reports in the window's language, built from their parts (the
// sentence and values of core/error_words.h, the report structs), never from the library's
// English text: a Chinese window shows no English sentence of the library's. An operating
// system's reason is worded too (system_words.h); other free-form parts (an HDF5 reason, a file
// name, a key name) appear as they are inside the translated words.

#include <exception>
#include <string>
#include <vector>

#include "aggpack/config/schema.h"
#include "aggpack/core/error.h"
#include "aggpack/core/error_words.h"
#include "aggpack/pack/dense_packer.h"
#include "aggpack/pack/progress.h"
#include "i18n.h"

namespace aggpack {
struct PipelineResult;
}

namespace aggpack::gui {

/// The catalogue entry of `sentence` (kSentence<Name>).
Text sentence_text(Sentence sentence);

/// The wording in the current language; a value that is a Sentence::kPhrase* word ("directory")
/// in it too, any other value as it is.
std::string wording_words(const Wording& wording);
/// As above; a value that is one of `worded`'s texts is worded as its sentence.
std::string wording_words(const Wording& wording, const std::vector<WordedValue>& worded);

/// An error in the current language: a refused value as "FIELD: VALUE is not allowed; allowed:
/// ..." (a limit: "... is over a limit ..."; FIELD and VALUE worded when they are sentences, a
/// solver deck field by its label in the deck panel), another aggpack error as its sentence,
/// std::bad_alloc as "out of memory", a std::system_error as "Error: what()", anything else as
/// an internal error with its what(). A ConfigError's origin ("gui: ", "--set K=V: ") is left
/// out: the panel is it.
std::string error_words(const std::exception& error);

/// A configuration key's allowed values in the current language: allowed_text()'s parts (its
/// rule and note, config/schema.h) worded; a range, a list of words or a key name as it is.
std::string allowed_words(const KeyView& key);

/// A key's default in the current language: default_text()'s, its words (Key::default_text,
/// "(none)") worded.
std::string default_words(const KeyView& key, const Value& default_value,
                          const std::string& default_from, const Wording& shown);

/// The packer's report line (in English, PackReport::summary()'s words).
std::string report_words(const PackReport& report);

/// The densifier's report line (in English, DensifyReport::summary()'s words).
std::string densify_words(const DensifyReport& report);

/// What a dense run fell short of, one line each (in English, dense_shortfalls()'s).
std::vector<std::string> shortfall_words(const PipelineResult& result);

}  // namespace aggpack::gui
