#pragma once
// HDF5 plumbing shared by the native file's writer (native.cpp) and reader (native_read.cpp).

#include <hdf5.h>

#include <string>

namespace aggpack::hdf5 {

// ---- HDF5 plumbing ----------------------------------------------------------------------------

// HDF5 prints its whole error stack to stderr by default; a corrupt file must instead become one
// FormatError. The previous handler is restored so that we do not change global state for others.
class SilenceHdf5Errors {
 public:
  SilenceHdf5Errors() {
    // HDF5 1.10 leaks free-list blocks on some corrupt-metadata error paths and then prints
    // "HDF5: infinite loop closing library" from its atexit handler, after our one-line error.
    // Skipping that handler is harmless: every file we open is closed before we return, and the
    // process's memory goes back to the OS at exit. Must run before the library initialises.
    static const bool is_atexit_skipped = [] { return H5dont_atexit() >= 0; }();
    (void)is_atexit_skipped;
    H5Eget_auto2(H5E_DEFAULT, &function_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~SilenceHdf5Errors() { H5Eset_auto2(H5E_DEFAULT, function_, data_); }
  SilenceHdf5Errors(const SilenceHdf5Errors&) = delete;
  SilenceHdf5Errors& operator=(const SilenceHdf5Errors&) = delete;

 private:
  H5E_auto2_t function_ = nullptr;
  void* data_ = nullptr;
};

// The innermost HDF5 error description (e.g. "truncated file: eof = ..."), which says more than
// the outer "unable to open file".
inline std::string hdf5_reason() {
  std::string reason;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_UPWARD,
      [](unsigned, const H5E_error2_t* error, void* data) -> herr_t {
        auto* text = static_cast<std::string*>(data);
        if (text->empty() && error->desc != nullptr) *text = error->desc;
        return 0;
      },
      &reason);
  H5Eclear2(H5E_DEFAULT);
  return reason.empty() ? "HDF5 error" : reason;
}

// Owns one hid_t and closes it with the matching H5*close.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Handle(Handle&& other) noexcept : id_(other.id_), closer_(other.closer_) { other.id_ = -1; }
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = other.id_;
      closer_ = other.closer_;
      other.id_ = -1;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { reset(); }

  [[nodiscard]] hid_t get() const { return id_; }
  [[nodiscard]] bool is_valid() const { return id_ >= 0; }
  /// Closes now and reports whether closing succeeded (H5Fclose flushes, so it can fail).
  bool close() {
    const herr_t status = id_ >= 0 ? closer_(id_) : 0;
    id_ = -1;
    return status >= 0;
  }

 private:
  void reset() {
    if (id_ >= 0) closer_(id_);
    id_ = -1;
  }
  hid_t id_ = -1;
  Closer closer_ = nullptr;
};

}  // namespace aggpack::hdf5
