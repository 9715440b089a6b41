// The MC6000's parameters as its PCP server serves them (INTERBUS manual 4.2): the INTERBUS face's
// translation between PCP and the drive core -- an index and subindex to a parameter number, the
// request's bytes to a value of the parameter's type, and the core's refusal to PCP's error class
// and code (docs/pcp.md, the table of negative confirmations). The values, checks, 85-SERR and
// timing are the core's (drive_parameters.hpp), the same that LUSTBUS reaches.
#pragma once

#include "ibs/devices/mc6000/drive_parameters.hpp"
#include "ibs/pcp/served.hpp"

namespace ibs::devices::mc6000 {

// The PCP error of a core refusal.
pcp::PcpError pcp_error(Refusal r);

class PcpServed final : public pcp::ServedParameters {
 public:
  explicit PcpServed(DriveAccess& drive) : drive_(&drive) {}
  // After a copy of the face that owns it: serve that face's drive.
  void serve(DriveAccess& drive) { drive_ = &drive; }

  [[nodiscard]] std::span<const pcp::ParameterInfo> table() const override { return drive_->parameters().table(); }
  void advance(Time now) override { drive_->advance(now); }
  pcp::PcpError read(Time now, std::uint16_t index, std::uint8_t subindex, pcp::Value& out) override;
  pcp::WriteAnswer write(Time now, std::uint16_t index, std::uint8_t subindex,
                         std::span<const std::uint8_t> data) override;
  [[nodiscard]] std::optional<pcp::Value> value(std::uint16_t number) const override {
    return drive_->parameters().value(number);
  }
  [[nodiscard]] std::uint8_t status_detail() const override { return drive_->parameters().serr(); }
  [[nodiscard]] bool fault() const override { return drive_->fault(); }

 private:
  DriveAccess* drive_;
};

}  // namespace ibs::devices::mc6000
