#include "core/io/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "core/error.h"
#include "core/interrupt.h"

namespace fs = std::filesystem;

namespace sylva {

void write_file_atomic(const std::string& path, const std::string& bytes) {
  fs::path target(path);
  if (target.filename().empty()) throw InputError(path, "cannot write: not a file name");
  fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::error_code ec;
  if (fs::is_directory(target, ec)) throw InputError(path, "cannot write: is a directory");
  if (!fs::is_directory(dir, ec)) throw InputError(path, "cannot write: folder does not exist");
  std::string hidden = ".";  // built by appends: GCC 12 misreports `"." + string&&` (-Wrestrict)
  hidden += target.filename().string();
  hidden += ".tmpXXXXXX";
  std::string tmpl = (dir / hidden).string();
  std::vector<char> name(tmpl.begin(), tmpl.end());
  name.push_back('\0');
  int fd = mkstemp(name.data());
  if (fd < 0) throw InputError(path, std::string("cannot write: ") + std::strerror(errno));
  auto fail = [&](int err) {
    close(fd);
    unlink(name.data());
    throw InputError(path, std::string("cannot write: ") + std::strerror(err));
  };
  size_t done = 0;
  while (done < bytes.size()) {
    ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail(errno);
    }
    done += static_cast<size_t>(n);
  }
  // mkstemp creates 0600; give the file the usual permissions under the umask.
  mode_t mask = umask(0);
  umask(mask);
  fchmod(fd, 0666 & ~mask);
  if (close(fd) != 0) {
    int err = errno;
    unlink(name.data());
    throw InputError(path, std::string("cannot write: ") + std::strerror(err));
  }
  if (interrupt_signal() != 0) {  // stopped: nothing new is put in place (core/interrupt.h)
    unlink(name.data());
    check_interrupt();
  }
  if (std::rename(name.data(), path.c_str()) != 0) {
    int err = errno;
    unlink(name.data());
    throw InputError(path, std::string("cannot write: ") + std::strerror(err));
  }
}

std::string make_temporary_folder_beside(const std::string& path) {
  const fs::path p(path);
  std::string name = ".";  // built by appends (GCC 12 -Wrestrict, as above)
  name += p.filename().string();
  name += ".tmpXXXXXX";
  std::string tmpl = (p.parent_path() / name).string();
  if (!mkdtemp(tmpl.data()))
    throw InputError(path, std::string("cannot write: ") + std::strerror(errno));
  return tmpl;
}

void write_folder_atomic(const std::string& dir,
                         const std::function<void(const std::string& staging)>& write) {
  std::error_code ec;
  const bool created = fs::create_directories(dir, ec);
  if (ec) throw InputError(dir, "cannot create the folder: " + ec.message());
  const std::string staging = make_temporary_folder_beside((fs::path(dir) / "files").string());
  try {
    write(staging);
    check_interrupt();
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(staging))
      files.push_back(entry.path());
    for (const fs::path& f : files)  // every name is checked before any file is moved
      if (fs::is_directory(fs::path(dir) / f.filename(), ec))
        throw InputError((fs::path(dir) / f.filename()).string(), "cannot write: is a directory");
    for (const fs::path& f : files) {
      fs::rename(f, fs::path(dir) / f.filename(), ec);
      if (ec)
        throw InputError((fs::path(dir) / f.filename()).string(), "cannot write: " + ec.message());
    }
  } catch (const InputError& e) {  // named by the file's place in `dir`, not in the staging folder
    fs::remove_all(staging, ec);
    if (created) fs::remove(dir, ec);
    std::string where = e.where();
    if (!where.starts_with(staging)) throw;
    where = (fs::path(dir) / fs::path(where).lexically_relative(staging)).string();
    const std::string what = e.what();
    throw InputError(where, what.substr(std::min(what.size(), e.where().size() + 2)));
  } catch (...) {
    fs::remove_all(staging, ec);
    if (created) fs::remove(dir, ec);
    throw;
  }
  fs::remove_all(staging, ec);
}

std::string read_file_bytes(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(path, "no such file");
  if (fs::is_directory(path, ec)) throw InputError(path, "is a directory, expected a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, std::string("cannot read: ") + std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace sylva
