#pragma once
// The operating system's reasons inside the library's sentences ("cannot read F: Permission
// denied", "died of signal 9 (Killed)") in the window's language: strerror's and strsignal's
// texts of the reasons a file, folder or worker process meets, by their errno or signal number.

#include <string>
#include <system_error>
#include <vector>

namespace aggpack::gui {

/// `text` in the current language when it is the system's words for a reason of the table below
/// (Chinese: the words glibc's zh_CN catalogue gives), else "" (a number, a name, or a reason
/// not in the table: shown as it is).
std::string system_reason_words(const std::string& text);

/// The reason of `code` (generic or system category) in the current language; its message as
/// the system gives it when not in the table.
std::string system_reason_words(const std::error_code& code);

/// The errno values and signals the table words (tests walk them).
std::vector<int> worded_errnos();
std::vector<int> worded_signals();
/// The table's Chinese words (the font loads their glyphs).
std::vector<const char*> system_reasons_chinese();

}  // namespace aggpack::gui
