#include "system_words.h"

#include <cerrno>
#include <csignal>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "i18n.h"

namespace aggpack::gui {

namespace {

struct Reason {
  int number;
  const char* chinese;
};

// The errno values a file, a folder, a pipe or a child process can give, in glibc's zh_CN words.
constexpr Reason kErrnos[] = {
    {EPERM, "不允许的操作"},
    {ENOENT, "没有那个文件或目录"},
    {EINTR, "被中断的系统调用"},
    {EIO, "输入/输出错误"},
    {ENXIO, "没有那个设备或地址"},
    {E2BIG, "参数列表过长"},
    {EBADF, "错误的文件描述符"},
    {ECHILD, "没有子进程"},
    {EAGAIN, "资源暂时不可用"},
    {ENOMEM, "无法分配内存"},
    {EACCES, "权限不够"},
    {EFAULT, "错误的地址"},
    {EBUSY, "设备或资源忙"},
    {EEXIST, "文件已存在"},
    {EXDEV, "无效的跨设备链接"},
    {ENODEV, "没有那个设备"},
    {ENOTDIR, "不是目录"},
    {EISDIR, "是一个目录"},
    {EINVAL, "无效的参数"},
    {ENFILE, "系统中打开的文件过多"},
    {EMFILE, "打开的文件过多"},
    {ETXTBSY, "文本文件忙"},
    {EFBIG, "文件过大"},
    {ENOSPC, "设备上没有空间"},
    {ESPIPE, "非法 seek 操作"},
    {EROFS, "只读文件系统"},
    {EMLINK, "过多的链接"},
    {EPIPE, "断开的管道"},
    {ENAMETOOLONG, "文件名过长"},
    {ENOSYS, "函数未实现"},
    {ENOTEMPTY, "目录非空"},
    {ELOOP, "符号连接的层数过多"},
    {EOVERFLOW, "对已定义的数据类型来说值过大"},
    {EOPNOTSUPP, "不支持的操作"},
    {ETIMEDOUT, "连接超时"},
    {ESTALE, "过旧的文件句柄"},
    {EDQUOT, "超出磁盘限额"},
    {ECANCELED, "操作已取消"},
};

// The signals a worker process may die of, in glibc's zh_CN words.
constexpr Reason kSignals[] = {
    {SIGHUP, "挂起"},
    {SIGINT, "中断"},
    {SIGQUIT, "退出"},
    {SIGILL, "非法指令"},
    {SIGTRAP, "追踪与中断点陷阱"},
    {SIGABRT, "已放弃"},
    {SIGBUS, "总线错误"},
    {SIGFPE, "浮点数例外"},
    {SIGKILL, "已杀死"},
    {SIGUSR1, "用户定义信号 1"},
    {SIGSEGV, "段错误"},
    {SIGUSR2, "用户定义信号 2"},
    {SIGPIPE, "断开的管道"},
    {SIGALRM, "闹钟"},
    {SIGTERM, "已终止"},
    {SIGXCPU, "超出 CPU 时限"},
    {SIGXFSZ, "文件大小超出限制"},
};

// The system's text of each reason (as the library's std::strerror, error_code::message and
// strsignal give it in this process) to its Chinese words. Built once.
const std::map<std::string, const char*>& chinese_by_text() {
  static const std::map<std::string, const char*> table = [] {
    std::map<std::string, const char*> by_text;
    for (const Reason& reason : kErrnos) {
      by_text.emplace(std::generic_category().message(reason.number), reason.chinese);
    }
    for (const Reason& reason : kSignals) {
      const char* name = ::strsignal(reason.number);
      if (name != nullptr) by_text.emplace(name, reason.chinese);
    }
    return by_text;
  }();
  return table;
}

}  // namespace

std::string system_reason_words(const std::string& text) {
  if (language() != Language::kChinese) return {};
  const auto& table = chinese_by_text();
  const auto found = table.find(text);
  return found == table.end() ? std::string() : std::string(found->second);
}

std::string system_reason_words(const std::error_code& code) {
  const std::string message = code.message();
  const std::string words = system_reason_words(message);
  return words.empty() ? message : words;
}

std::vector<int> worded_errnos() {
  std::vector<int> numbers;
  for (const Reason& reason : kErrnos) numbers.push_back(reason.number);
  return numbers;
}

std::vector<int> worded_signals() {
  std::vector<int> numbers;
  for (const Reason& reason : kSignals) numbers.push_back(reason.number);
  return numbers;
}

std::vector<const char*> system_reasons_chinese() {
  std::vector<const char*> words;
  for (const Reason& reason : kErrnos) words.push_back(reason.chinese);
  for (const Reason& reason : kSignals) words.push_back(reason.chinese);
  return words;
}

}  // namespace aggpack::gui
