#include "tellus/dem/gdal_support.hpp"

#include <mutex>

#include <cpl_error.h>
#include <spdlog/spdlog.h>

namespace tellus::gdal {
namespace {

void CPL_STDCALL logGdalMessage(CPLErr level, CPLErrorNum number, const char* message) {
  spdlog::debug("GDAL ({}, {}): {}", int(level), number, message);
}

}  // namespace

void ensureRegistered() {
  static std::once_flag once;
  std::call_once(once, [] {
    GDALAllRegister();
    CPLSetErrorHandler(logGdalMessage);
  });
}

std::string lastErrorMessage() {
  const char* message = CPLGetLastErrorMsg();
  return message ? std::string(message) : std::string();
}

std::string lastError() {
  const std::string message = lastErrorMessage();
  return message.empty() ? std::string("unknown GDAL error") : message;
}

}  // namespace tellus::gdal
