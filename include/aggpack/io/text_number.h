#pragma once
// Real numbers for text formats whose readers limit a field's width. Abaqus and CalculiX read at
// most 20 characters per number (a longer one is an input error or, worse, silently cut:
// "6.566569607759087e-05" is read as "6.566569607759087e-0"); LS-DYNA's comma-separated fields
// must not be wider than the fixed column they stand for. Formats without such a rule use the
// shortest round-trip form (std::to_chars).

#include <string>

namespace aggpack {

/// Appends `value` in at most `max_chars` characters (>= 7, enough for any double to 1 digit):
/// the shortest decimal form that reads back to exactly `value` when it fits; otherwise the form
/// with the most significant digits that fits, plain ("-0.01234567890123457") or scientific with a
/// compact exponent ("-1.10062921185074e-5": no '+', no leading zeros; Fortran and C readers
/// accept it, ccx 2.20 included). In 20 characters that keeps >= 15 significant digits (relative
/// error <= 5e-15) for 1e-9 <= |value| < 1e100, >= 14 down to 1e-99 and >= 13 for any double.
/// \throw InvalidInput when max_chars < 7.
void append_number_fitting(std::string& out, double value, int max_chars);

/// The widest number Abaqus and CalculiX read (characters). aggpack writes every real number of
/// its finite-element text formats (.inp, rock.dat, APDL) within it.
inline constexpr int kFeNumberWidth = 20;

}  // namespace aggpack
