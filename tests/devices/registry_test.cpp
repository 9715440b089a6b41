// The registry of drive kinds (devices/registry.hpp): every kind builds its emulator and its
// master driver from its descriptor alone, and the drive-neutral parts -- trace adapters, the
// trace reader's vocabulary -- find the drives through it.
#include "ibs/devices/registry.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "ibs/canlust/parameter_client.hpp"
#include "ibs/devices/cda3000/bus_face.hpp"
#include "ibs/devices/cda3000/parameters.hpp"
#include "ibs/devices/dfs1/bus_face.hpp"
#include "ibs/devices/dfs1/parameters.hpp"
#include "ibs/devices/drives.hpp"
#include "ibs/devices/mc6000/capture.hpp"
#include "ibs/devices/mc6000/lustbus_face.hpp"
#include "ibs/devices/trace_adapters.hpp"
#include "ibs/devices/vf1000/capture.hpp"
#include "ibs/devices/vf1000/lustbus_face.hpp"
#include "ibs/dfs1/host.hpp"
#include "ibs/drivecom/sequencer.hpp"
#include "ibs/lustbus/host.hpp"
#include "ibs/lustbus/line.hpp"
#include "ibs/lustbus/receiver.hpp"

namespace ibs::devices {
namespace {

TEST(Registry, ListsEveryDriveKindOnceSortedByName) {
  const auto kinds = drive_kinds();
  ASSERT_FALSE(kinds.empty());
  std::vector<std::string_view> names;
  for (const DriveKind& k : kinds) {
    ASSERT_NE(k.descriptor, nullptr);
    ASSERT_NE(k.make_emulator, nullptr);
    names.push_back(k->name());
    EXPECT_EQ(find_drive_kind(k->name()), &k);
  }
  EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
  EXPECT_EQ(std::adjacent_find(names.begin(), names.end()), names.end());
  EXPECT_EQ(find_drive_kind("mc7000"), nullptr);
  EXPECT_EQ(drive_kind_names(", ", " or ", "\""), "\"mc6000\" or \"vf1000\"");
}

// Every kind, with the settings its descriptor takes by default: a configuration the bus takes,
// an emulator that samples, a driver that cycles, both with the words the configuration gives.
TEST(Registry, EveryKindBuildsItsEmulatorAndDriverFromItsDescriptor) {
  for (const DriveKind& k : drive_kinds()) {
    SCOPED_TRACE(std::string(k->name()));
    const DriveFacts& f = k->facts();
    EXPECT_FALSE(f.title.empty());
    EXPECT_FALSE(f.unit.empty());
    EXPECT_GT(f.sample_period, Duration{0});
    const Configuration c = k->configure(DeviceSettings{});
    EXPECT_TRUE(c.id_code.decodable());
    EXPECT_EQ(c.id_code.pd_words(), static_cast<int>(c.pd_words));
    EXPECT_EQ(c.id_code.pcp_words(), static_cast<int>(c.pcp_words));

    auto emulator = k.make_emulator(c, DeviceStart::operational, Time{0});
    ASSERT_NE(emulator, nullptr);
    EXPECT_EQ(emulator->state(), drivecom::State::start_up_inhibit);
    std::array<Word, 4> m2s{0x0006, 0, 0, 0};  // SHUTDOWN
    std::array<Word, 4> s2m{};
    std::array<Word, 4> pcp_m2s{};
    std::array<Word, 4> pcp_s2m{};
    emulator->bus_cycle(f.sample_period);
    emulator->sample({std::span<const Word>(m2s.data(), c.pd_words), std::span<Word>(s2m.data(), c.pd_words),
                      std::span<const Word>(pcp_m2s.data(), c.pcp_words), std::span<Word>(pcp_s2m.data(), c.pcp_words)},
                     f.sample_period);
    EXPECT_EQ(emulator->state(), drivecom::State::ready);
    EXPECT_EQ(drivecom::decode_state(s2m[0]), drivecom::State::ready) << std::hex << s2m[0];
    const auto copy = emulator->clone();
    EXPECT_EQ(copy->state(), drivecom::State::ready);
    EXPECT_FALSE(emulator->error_number().has_value());

    auto driver = k->make_driver(c);
    ASSERT_NE(driver, nullptr);
    EXPECT_EQ(driver->unit(), f.unit);
    std::array<Word, 4> out{};
    std::array<Word, 4> pcp_out{};
    const DriverIo io{std::span<const Word>(s2m.data(), c.pd_words), std::span<Word>(out.data(), c.pd_words),
                      std::span<const Word>(pcp_s2m.data(), c.pcp_words), std::span<Word>(pcp_out.data(), c.pcp_words)};
    driver->initial(io);
    driver->sequencer().request(drivecom::Target::on, Time{0});
    driver->cycle(io, f.sample_period);
    EXPECT_EQ(out[0] & drivecom::cw::kDrivecomMask, 0x0007) << "POWER-ON from READY";
    EXPECT_FALSE(k->explain_status(s2m[0]).empty());
  }
}

// The fault campaign finds each kind's part through the registry (campaign_profile.hpp): a ring
// its descriptor takes, and a model whose start is what the kind's emulator holds and whose
// writes keep to (or, where meant to, leave) the documented ranges.
TEST(Registry, EveryKindHasACampaignProfileTheEmulatorAgreesWith) {
  for (const DriveKind& k : drive_kinds()) {
    SCOPED_TRACE(std::string(k->name()));
    ASSERT_NE(k.campaign, nullptr);
    EXPECT_EQ(k.campaign->kind(), k->name());
    CampaignRandom rng(1);
    const std::vector<CampaignRingDevice> ring = k.campaign->ring(rng);
    ASSERT_FALSE(ring.empty());
    for (const CampaignRingDevice& r : ring) {
      SCOPED_TRACE(r.name);
      EXPECT_NO_THROW(k->check_watchdog(r.settings));
      const Configuration c = k->configure(r.settings);
      EXPECT_LT(r.phase, k->facts().sample_period);
      auto emulator = k.make_emulator(c, DeviceStart::operational, Time{0});
      const CampaignDevice d = k.campaign->device(r, *emulator, rng);
      EXPECT_EQ(d.period, k->facts().sample_period);
      EXPECT_FALSE(d.description.empty());
      EXPECT_EQ(k.campaign->software_resets(*emulator), 0U);
      EXPECT_FALSE(k.campaign->layout_mismatch(*emulator));
      std::vector<CampaignStoreEntry> store;
      k.campaign->read_store(*emulator, store);
      if (!d.has_channel) {
        EXPECT_TRUE(d.params.empty());
        EXPECT_TRUE(store.empty());
        EXPECT_GT(d.watchdog_fixed_ms, 0);
        continue;
      }
      ASSERT_FALSE(d.params.empty());
      EXPECT_FALSE(d.writes.empty());
      const auto watchdog = std::find_if(d.params.begin(), d.params.end(),
                                         [&d](const CampaignParam& p) { return p.number == d.watchdog_parameter; });
      ASSERT_NE(watchdog, d.params.end());
      EXPECT_EQ(watchdog->initial, *r.settings.watchdog_ms);
      for (const CampaignParam& p : d.params) {
        if (p.role == CampaignRole::device_owned) continue;
        SCOPED_TRACE(p.number);
        const auto e = std::find_if(store.begin(), store.end(),
                                    [&p](const CampaignStoreEntry& x) { return x.number == p.number; });
        ASSERT_NE(e, store.end());
        EXPECT_EQ(e->ram, p.initial);
        if (p.eeprom && e->eeprom) {
          EXPECT_EQ(*e->eeprom, p.initial);
        }
        EXPECT_GE(p.factory, p.min);
        EXPECT_LE(p.factory, p.max);
      }
      for (const CampaignWrites& w : d.writes) {
        SCOPED_TRACE(w.number);
        const auto p = std::find_if(d.params.begin(), d.params.end(),
                                    [&w](const CampaignParam& x) { return x.number == w.number; });
        ASSERT_NE(p, d.params.end());
        EXPECT_EQ(p->role, CampaignRole::normal);
        for (const std::int64_t v : w.in_range) EXPECT_TRUE(v >= p->min && v <= p->max) << v;
        for (const std::int64_t v : w.out_of_range) EXPECT_TRUE(v < p->min || v > p->max) << v;
      }
    }
  }
}

// The watchdog's raw value and the channel's timeouts, as the manuals give them.
TEST(Registry, CampaignProfilesTurnWatchdogValuesAndRequestsIntoTimes) {
  const CampaignProfile& vf = *find_drive_kind("vf1000")->campaign;
  EXPECT_EQ(vf.watchdog_ms(65), 100);  // INTERBUS manual 4.1.1: 50 ms steps, rounded up
  EXPECT_EQ(vf.watchdog_ms(100), 100);
  EXPECT_LE(vf.watchdog_ms(65535), 0);  // off
  EXPECT_EQ(vf.request_timeout(ParamOp::write, 71, 1), 2s);
  const CampaignProfile& mc = *find_drive_kind("mc6000")->campaign;
  EXPECT_EQ(mc.watchdog_ms(30), 30);  // 409-BUTWD in ms
  EXPECT_LE(mc.watchdog_ms(0), 0);    // off
  EXPECT_EQ(mc.request_timeout(ParamOp::read, 4, 0), 1s);  // Initiate + request, 500 ms each
  EXPECT_EQ(mc.request_timeout(ParamOp::write, 4, 1), 500ms + 10500ms);  // factory defaults
  ASSERT_TRUE(mc.download().has_value());
  EXPECT_EQ(mc.download()->parameter, 80);
  EXPECT_FALSE(vf.download().has_value());
}

TEST(Registry, EveryKindRefusesASettingWithTheSettingNamed) {
  for (const DriveKind& k : drive_kinds()) {
    SCOPED_TRACE(std::string(k->name()));
    DeviceSettings s;
    s.watchdog_ms = -1;
    try {
      k->check_watchdog(s);
      ADD_FAILURE() << "a negative watchdog time was taken";
    } catch (const SettingsError& e) {
      EXPECT_EQ(e.setting(), "watchdog_ms") << e.what();
    }
  }
}

TEST(Registry, TheTraceVocabularyIsTheKindsAndDrivecomsTargets) {
  const trace::Vocabulary v = trace_vocabulary();
  ASSERT_EQ(v.devices.size(), drive_kinds().size());
  for (std::size_t i = 0; i < v.devices.size(); ++i) EXPECT_EQ(v.devices[i], drive_kinds()[i]->name());
  EXPECT_EQ(std::vector<std::string_view>(v.targets.begin(), v.targets.end()),
            (std::vector<std::string_view>{"start-up-inhibit", "ready", "on", "enabled"}));
  try {
    (void)parse_trace("# format: ibs-trace 1\n# device: mc7000\n", "x.trace");
    ADD_FAILURE();
  } catch (const trace::TraceError& e) {
    EXPECT_STREQ(e.what(), "x.trace:2: device: 'mc7000' is not one of mc6000, vf1000");
  }
}

// A trace read without the vocabulary still meets the registry before anything runs.
TEST(Registry, AdaptersRefuseAnUnknownDriveOrTargetOnItsHeaderLine) {
  const trace::Trace unknown =
      trace::parse("# format: ibs-trace 1\n# device: cda3000\n# words: pd\n0, 0000, 0240\n", "u.trace");
  try {
    (void)make_device_side(unknown);
    ADD_FAILURE();
  } catch (const trace::TraceError& e) {
    EXPECT_STREQ(e.what(), "u.trace:2: device: 'cda3000' is not one of mc6000, vf1000");
  }
  const trace::Trace target = trace::parse(
      "# format: ibs-trace 1\n# device: vf1000\n# words: pd\n# request: state running\n0, 0000 0000 0000, 0240 0000 0000\n",
      "t.trace");
  try {
    (void)make_master_side(target);
    ADD_FAILURE();
  } catch (const trace::TraceError& e) {
    EXPECT_STREQ(e.what(), "t.trace:4: request: state target 'running' is not one of start-up-inhibit, ready, on, enabled");
  }
}

TEST(Registry, TracesOfAChannelAnotherDriveHasAreRefused) {
  const trace::Trace t =
      trace::parse("# format: ibs-trace 1\n# device: vf1000\n# words: pcp\n0, 0000, 0000\n", "p.trace");
  try {
    (void)make_explainer(t);
    ADD_FAILURE();
  } catch (const trace::TraceError& e) {
    EXPECT_STREQ(e.what(), "p.trace:3: words: pcp is not served for device vf1000 (PCP is the MC6000's)");
  }
}

// ---- The registry of drive and bus (drives.hpp) ----------------------------------------------

using namespace std::chrono_literals;

std::vector<std::string> pair_names(const std::vector<DriveOnBus>& pairs) {
  std::vector<std::string> v;
  for (const DriveOnBus& p : pairs) v.push_back(std::string(p.drive->name) + "/" + std::string(to_string(p.bus)));
  return v;
}

// The pairs are exactly the faces the wings declare: each wing's face function is what the
// registry hands out, and no drive speaks a bus its wing has no face for.
TEST(DriveRegistry, ThePairsAreWhatTheWingsDeclare) {
  EXPECT_EQ(pair_names(drive_bus_pairs()),
            (std::vector<std::string>{"cda3000/CANLust", "dfs1/DFS-1", "mc6000/INTERBUS", "mc6000/LUSTBUS",
                                      "vf1000/INTERBUS", "vf1000/LUSTBUS"}));
  const Drive* vf = find_drive("vf1000");
  const Drive* mc = find_drive("mc6000");
  const Drive* dfs = find_drive("dfs1");
  const Drive* cda = find_drive("cda3000");
  ASSERT_TRUE(vf && mc && dfs && cda);
  EXPECT_EQ(vf->interbus, find_drive_kind("vf1000"));
  EXPECT_EQ(mc->interbus, find_drive_kind("mc6000"));
  EXPECT_EQ(vf->lustbus, &vf1000::lustbus_face());
  EXPECT_EQ(mc->lustbus, &mc6000::lustbus_face());
  EXPECT_EQ(dfs->dfs1, &dfs1::bus_face());
  EXPECT_EQ(cda->canlust, &cda3000::bus_face());
  EXPECT_EQ(vf->lustbus->family, lustbus::Family::standard);
  EXPECT_EQ(mc->lustbus->family, lustbus::Family::enhanced);
  // Every INTERBUS kind is a drive of the registry, with the capture facts its wing declares.
  std::size_t interbus = 0;
  for (const DriveKind& k : drive_kinds()) {
    const Drive* d = find_drive(k->name(), Bus::interbus);
    ASSERT_NE(d, nullptr) << k->name();
    EXPECT_EQ(d->interbus, &k);
    ++interbus;
  }
  EXPECT_EQ(drives_on(Bus::interbus).size(), interbus);
  EXPECT_EQ(find_drive_kind("vf1000")->capture, &vf1000::capture_face());
  EXPECT_EQ(find_drive_kind("mc6000")->capture, &mc6000::capture_face());
  // Sorted by name, each once; a drive is found under a bus only if it speaks it.
  std::vector<std::string_view> names;
  for (const Drive& d : drives()) names.push_back(d.name);
  EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
  EXPECT_EQ(std::adjacent_find(names.begin(), names.end()), names.end());
  EXPECT_EQ(find_drive("dfs1", Bus::lustbus), nullptr);
  EXPECT_EQ(find_drive("vf1000", Bus::canlust), nullptr);
  EXPECT_EQ(find_drive("mc7000"), nullptr);
  // The names the command line's messages list (docs/lustbus.md: "vf1000@ADDR or mc6000@ADDR").
  EXPECT_EQ(drive_names(Bus::lustbus, ", ", " or ", "@ADDR"), "vf1000@ADDR or mc6000@ADDR");
  EXPECT_EQ(drive_names(Bus::dfs1, ", ", " or ", "@UID"), "dfs1@UID");
  EXPECT_EQ(drive_names(Bus::canlust, ", ", " or "), "cda3000");
}

// INTERBUS: the drive's master driver reads parameter 85 through the emulator's parameter channel
// (the VF1000's communication word, the MC6000's PCP), both cycled in memory.
void read_on_interbus(const DriveKind& k) {
  const Configuration c = k->configure(DeviceSettings{});
  auto emulator = k.make_emulator(c, DeviceStart::operational, Time{0});
  auto driver = k->make_driver(c);
  ASSERT_TRUE(emulator && driver);
  std::array<Word, 4> m2s{};
  std::array<Word, 4> s2m{};
  std::array<Word, 4> pcp_m2s{};
  std::array<Word, 4> pcp_s2m{};
  const DriverIo io{std::span<const Word>(s2m.data(), c.pd_words), std::span<Word>(m2s.data(), c.pd_words),
                    std::span<const Word>(pcp_s2m.data(), c.pcp_words), std::span<Word>(pcp_m2s.data(), c.pcp_words)};
  emulator->output(std::span<Word>(s2m.data(), c.pd_words));
  driver->initial(io);
  const ParamId id = driver->parameters().submit(ParamOp::read, 85, 0);
  ASSERT_NE(id, 0U);
  const Duration period = k->facts().sample_period;
  for (Time t = period; t <= Time{8s} && !driver->parameters().status(id).done(); t += period) {
    driver->cycle(io, t);
    emulator->bus_cycle(t);
    emulator->sample({std::span<const Word>(m2s.data(), c.pd_words), std::span<Word>(s2m.data(), c.pd_words),
                      std::span<const Word>(pcp_m2s.data(), c.pcp_words), std::span<Word>(pcp_s2m.data(), c.pcp_words)},
                     t);
  }
  EXPECT_EQ(driver->parameters().status(id).kind, ParamKind::value) << driver->parameters().describe(id);
}

// LUSTBUS: the face behind a lustbus::Receiver at address 1 on the simulated line answers the
// host's ENQUIRY of 91-TYPE, which 5.2's scan reads from every LUSTBUS device.
void read_on_lustbus(const LustbusFace& face) {
  LustbusEmulated e = face.make(LustbusFaceOptions{});
  ASSERT_TRUE(e.responder && e.advance && e.line_baud);
  EXPECT_EQ(e.line_baud(), 9600U);
  const auto p = face.find_parameter("91");
  ASSERT_TRUE(p.has_value());
  EXPECT_EQ(face.find_parameter(p->name)->number, 91);
  lustbus::Receiver receiver(*e.responder, 1);
  lustbus::Host host;
  lustbus::Line line(9600);
  line.attach(host);
  line.attach(receiver);
  const auto code = lustbus::parameter_code(face.family, p->number, false);
  ASSERT_TRUE(code.has_value());
  const auto s = host.submit(lustbus::enquiry(1, *code));
  ASSERT_TRUE(s);
  ASSERT_TRUE(line.run_until_idle(line.now() + 5s));
  const lustbus::Outcome* o = host.outcome(s.id);
  ASSERT_NE(o, nullptr);
  ASSERT_EQ(o->kind, lustbus::OutcomeKind::value) << lustbus::describe(*o);
  EXPECT_TRUE(lustbus::parse_typed(face.family, p->type, o->value.view()).ok()) << o->value.view();
  // A rate the drive does not run at is refused when the face is made (LUSTBUS manual 4).
  LustbusFaceOptions odd;
  odd.baud = 1234;
  EXPECT_THROW((void)face.make(odd), std::invalid_argument);
}

// DFS-1: the controller answers a read of its baud rate code with the code of the rate it was
// made for (docs/dfs1.md).
void read_on_dfs1(const dfs1::Dfs1Face& face) {
  auto c = face.make(7, 9600);
  ASSERT_NE(c, nullptr);
  const ::ibs::dfs1::EncodedFrame e = ::ibs::dfs1::encode(::ibs::dfs1::request::read_parameter(7, dfs1::kBaudCode));
  c->receive(e.span(), Time{0});
  const auto due = c->next_deadline();
  ASSERT_TRUE(due.has_value());
  ::ibs::dfs1::FrameDecoder d;
  std::optional<::ibs::dfs1::Frame> answer;
  for (const std::uint8_t b : c->pending(*due)) {
    if (d.push(b).status == ::ibs::dfs1::DecodeStatus::frame) answer = d.frame();
  }
  ASSERT_TRUE(answer.has_value());
  ASSERT_TRUE(answer->is_ack());
  EXPECT_EQ(answer->value_at(0), *dfs1::code_for_baud(9600));
}

// CANLust: a commissioned CDA3000 at address 1 answers the parameter client's read of 360-DISP
// (7.1.3) with its value, frames passed in memory.
void read_on_canlust(const CanlustFace& face) {
  auto drive = face.make(CanlustFaceOptions{});
  ASSERT_NE(drive, nullptr);
  drive->power_on(Time{0});
  canlust::ParameterClient client;
  const auto s = client.submit(canlust::read(1, cda3000::kDisp));
  ASSERT_TRUE(s);
  for (Time t{0}; t <= Time{2s} && client.poll(s.id).state != canlust::RequestState::done; t += 100us) {
    client.step(t);
    while (auto f = client.take_frame()) drive->receive(*f, t);
    drive->step(t);
    while (auto f = drive->take_frame()) client.receive(*f, t);
  }
  const canlust::Poll p = client.poll(s.id);
  ASSERT_EQ(p.state, canlust::RequestState::done);
  ASSERT_EQ(p.outcome->kind, canlust::OutcomeKind::done) << canlust::describe(*p.outcome);
  EXPECT_EQ(p.outcome->value, *drive->value(cda3000::kDisp));
}

// CANLust: what `ibs run` knows of a drive's parameters comes from its face, in the table's words
// (CANLust manual 4.3.1 / 5.5.5): names and numbers, read-only and text parameters, values parsed and
// formatted; and the master the face makes drives the drives it makes to DRIVECOM "operation
// enabled" (5.4.2) with a reference, frames passed in memory.
TEST(DriveRegistry, CanlustFaceLooksParametersUpAndRunsItsDrives) {
  const Drive* d = find_drive("cda3000", Bus::canlust);
  ASSERT_NE(d, nullptr);
  const CanlustFace& face = *d->canlust;
  EXPECT_EQ(face.title, "CDA3000");
  const auto cawdg = face.find_parameter("CAWDG");
  ASSERT_TRUE(cawdg);
  EXPECT_EQ(cawdg->number, 574);
  EXPECT_EQ(cawdg->name, "574-CAWDG");
  EXPECT_TRUE(cawdg->writable);
  EXPECT_FALSE(cawdg->is_string);
  EXPECT_EQ(face.find_parameter("574-CAWDG")->number, 574);
  EXPECT_FALSE(face.find_parameter("CAWDX"));
  EXPECT_FALSE(face.parameter(9999));
  EXPECT_FALSE(face.parameter(cda3000::kReff)->writable);  // 406-REFF: the drive's actual reference
  EXPECT_TRUE(face.parameter(cda3000::kName)->is_string);
  EXPECT_EQ(face.parse_value(574, "300").error, "574-CAWDG: 300 ms is above the maximum 255 ms");
  EXPECT_EQ(face.parse_value(cda3000::kReff, "20.5").wire, 0x00148000U);
  EXPECT_EQ(face.format_value(cda3000::kReff, 0x00148000U), "20.5 Hz");

  CanlustMasterOptions mo;
  mo.drives = {{1, 2, 400.0}, {2, 2, 400.0}};
  const auto master = face.make_master(mo);
  std::vector<std::unique_ptr<CanlustDrive>> drives;
  for (const std::uint8_t a : {std::uint8_t{1}, std::uint8_t{2}}) {
    CanlustFaceOptions o;
    o.address = a;
    o.status_ms = 20;
    drives.push_back(face.make(o));
    drives.back()->power_on(Time{0});
    EXPECT_EQ(drives.back()->address(), a);
  }
  EXPECT_EQ(*drives[0]->value(575), 20U);  // 575-CASCY as the options stored it
  bool asked = false;
  for (Time t{0}; t <= Time{2s}; t += 1ms) {
    if (!asked && t >= Time{100ms}) {
      master->system_start(t);
      EXPECT_TRUE(master->request(1, drivecom::Target::enabled, t));
      EXPECT_FALSE(master->set_reference_hz(1, 20.0));
      asked = true;
    }
    master->cycle(t);
    while (auto f = master->take_frame()) {
      for (auto& x : drives) x->receive(*f, t);
    }
    for (auto& x : drives) {
      x->step(t);
      while (auto f = x->take_frame()) master->receive(*f, t);
    }
  }
  EXPECT_EQ(drives[0]->system_state(), canlust::SystemState::start);
  EXPECT_EQ(drives[0]->state(), drivecom::State::enabled);
  EXPECT_DOUBLE_EQ(drives[0]->reference_hz(), 20.0);
  EXPECT_EQ(master->set_reference_hz(7, 1.0), "not a configured drive");
  EXPECT_FALSE(master->request(7, drivecom::Target::enabled, Time{2s}));
  const auto status = master->status_text(1);
  ASSERT_TRUE(status);
  EXPECT_NE(status->find(std::string(drivecom::to_string(drivecom::State::enabled))), std::string::npos) << *status;
  const CanlustSubmission refused = master->write(1, 574, "300");
  EXPECT_FALSE(refused);
  EXPECT_EQ(refused.error, "574-CAWDG: 300 ms is above the maximum 255 ms");
}

// What `ibs canlust read|write|describe|start|stop|monitor` and `ibs decode` take from the face
// instead of the wing: the JSON number, the longer wait for SAVE/PROG (4.3.3), the description
// items (D29), the status word, the actual frequency (5.5.6, D25) and a frame in words.
TEST(DriveRegistry, CanlustFaceGivesTheClientCommandsTheirWords) {
  const std::vector<const Drive*> on = drives_on(Bus::canlust);
  ASSERT_EQ(on.size(), 1U);  // the client commands take the one drive; a second needs --drive
  const CanlustFace& face = *on.front()->canlust;
  EXPECT_EQ(face.short_title, "CDA");
  EXPECT_EQ(face.parameter(cda3000::kReff)->type, canlust::DataType::int32q16);
  EXPECT_EQ(face.parameter(574)->type, canlust::DataType::usign8);
  EXPECT_EQ(face.number_of(cda3000::kReff, 0xFFEB8000U), -0x148000);  // -20.5 Hz, raw Q16
  EXPECT_EQ(face.number_of(574, 200), 200);
  EXPECT_EQ(face.number_of(9999, 0xFFFFFFFFU), 0xFFFFFFFFLL);  // not in the table: the wire image
  EXPECT_EQ(face.write_timeout(cda3000::kSave), Duration(2s));
  EXPECT_EQ(face.write_timeout(cda3000::kProg), Duration(2s));
  EXPECT_FALSE(face.write_timeout(574));

  const std::array<std::uint32_t, 8> items = {static_cast<std::uint32_t>(canlust::DataType::usign8), 0, 255, 0,
                                              0x03,  // writable, flash
                                              0x44574143U /* "CAWD" */, 0x47U /* "G" */, 0x736DU /* "ms" */};
  const auto d = face.read_description(items);
  ASSERT_TRUE(d);
  EXPECT_EQ(d->type, canlust::DataType::usign8);
  EXPECT_EQ(d->max, 255U);
  EXPECT_TRUE(d->writable);
  EXPECT_TRUE(d->flash);
  EXPECT_FALSE(d->after_mains_reset);
  EXPECT_EQ(d->short_name, "CAWDG");
  EXPECT_EQ(d->unit, "ms");
  EXPECT_FALSE(face.read_description(std::span(items).first(3)));

  EXPECT_EQ(face.explain_status_word(0x0637), "0637 ENABLED, remote, reference reached");
  EXPECT_DOUBLE_EQ(face.hz_from_wire(canlust::ValueWidth::int32q16, 0x148000), 20.5);
  EXPECT_DOUBLE_EQ(face.hz_from_wire(canlust::ValueWidth::int16q0, -20), -20.0);

  const canlust::IdentifierMap ids{};
  canlust::CanFrame f;
  f.id = 663;
  f.dlc = 6;
  f.data = {0x01, 0x00, 0x00, 0x80, 0x14, 0x00, 0, 0};
  const CanlustFrameText e = face.explain_frame(f, ids, *canlust::process_layout_for_cacnf(4));
  ASSERT_TRUE(e.id);
  EXPECT_EQ(e.id->address, 1U);
  EXPECT_EQ(e.text, "control CDA 1: EasyDrive 0001 STR; reference 20.5 Hz");
  f.id = 0x7F0;
  EXPECT_FALSE(face.explain_frame(f, ids, *canlust::process_layout_for_cacnf(2)).id);
}

TEST(DriveRegistry, EveryDriveAnswersAParameterReadOnEveryBusItSpeaks) {
  for (const DriveOnBus& p : drive_bus_pairs()) {
    SCOPED_TRACE(std::string(p.drive->name) + " on " + std::string(to_string(p.bus)));
    switch (p.bus) {
      case Bus::interbus: read_on_interbus(*p.drive->interbus); break;
      case Bus::lustbus: read_on_lustbus(*p.drive->lustbus); break;
      case Bus::dfs1: read_on_dfs1(*p.drive->dfs1); break;
      case Bus::canlust: read_on_canlust(*p.drive->canlust); break;
    }
  }
}

// The byte-log reader's lookup finds each LUSTBUS drive's parameters by family and number.
TEST(DriveRegistry, TheByteLogLookupIsTheFacesTables) {
  const lustbus::ParameterLookup lookup = lustbus_parameter_lookup();
  for (const Drive* d : drives_on(Bus::lustbus)) {
    SCOPED_TRACE(std::string(d->name));
    const auto f = lookup(d->lustbus->family, 91);
    ASSERT_TRUE(f.has_value());
    EXPECT_EQ(f->name, d->lustbus->find_parameter("91")->name);
  }
  EXPECT_FALSE(lookup(lustbus::Family::standard, 100).has_value()) << "2.4.1: two digits";
}

// The settings a LUSTBUS face takes are declared for LUSTBUS; a setting the drive's INTERBUS face
// declares for LUSTBUS too is the same one in its LUSTBUS face's list, so that `ibs lustbus emulate`
// and a scenario mean one thing by its name.
TEST(DriveRegistry, LustbusFacesDeclareTheirSettingsForLustbus) {
  for (const Drive* d : drives_on(Bus::lustbus)) {
    SCOPED_TRACE(std::string(d->name));
    for (const SettingSpec& s : d->lustbus->settings) {
      EXPECT_TRUE(uses(s.faces, SettingFace::lustbus)) << s.name;
      EXPECT_LE(s.min, s.fallback);
      EXPECT_LE(s.fallback, s.max);
      EXPECT_FALSE(s.seed.empty());
      EXPECT_FALSE(s.meaning.empty());
    }
    if (d->interbus == nullptr) continue;
    for (const SettingSpec& s : (*d->interbus)->settings()) {
      EXPECT_TRUE(uses(s.faces, SettingFace::interbus)) << s.name << ": a scenario key must be INTERBUS's";
      if (!uses(s.faces, SettingFace::lustbus)) continue;
      const SettingSpec* l = find_setting(d->lustbus->settings, s.name);
      ASSERT_NE(l, nullptr) << s.name << " is declared for LUSTBUS but not in the LUSTBUS face's list";
      EXPECT_EQ(l->kind, s.kind);
      EXPECT_EQ(l->fallback, s.fallback);
    }
  }
}

// LUSTBUS manual 10: a KEYPAD widens each drive's reaction times (servo 1...25 -> 1...30 ms, inverter
// 1...30 -> 1...60 ms); the face's declared `keypad` setting is what makes the drive draw them.
TEST(DriveRegistry, AKeypadWidensTheLustbusReactionTimes) {
  const std::map<std::string_view, std::pair<Duration, Duration>> table = {{"mc6000", {25ms, 30ms}},
                                                                          {"vf1000", {30ms, 60ms}}};
  for (const Drive* d : drives_on(Bus::lustbus)) {
    SCOPED_TRACE(std::string(d->name));
    const auto row = table.find(d->name);
    ASSERT_NE(row, table.end()) << "a LUSTBUS drive without its row of 10's table here";
    const SettingSpec* keypad = find_setting(d->lustbus->settings, "keypad");
    ASSERT_NE(keypad, nullptr);
    const auto code = lustbus::parameter_code(d->lustbus->family, 91, false);
    ASSERT_TRUE(code.has_value());
    for (const bool with : {false, true}) {
      LustbusFaceOptions o;
      o.seed = 7;
      if (with) o.settings.set_boolean(keypad->name, true);
      LustbusEmulated e = d->lustbus->make(o);
      Duration longest{};
      for (int i = 0; i < 400; ++i) {
        const auto a = e.responder->enquiry(*code, lustbus::Context{1, Time{std::chrono::milliseconds(100 * i)}});
        ASSERT_EQ(a.reply, lustbus::Reply::text);
        longest = std::max(longest, a.reaction);
      }
      const Duration without_keypad = row->second.first;
      const Duration with_keypad = row->second.second;
      if (with) {
        EXPECT_GT(longest, without_keypad);
        EXPECT_LE(longest, with_keypad);
      } else {
        EXPECT_LE(longest, without_keypad);
      }
    }
  }
}

// The `local NAME = { [0] = "...", ... }` table of the dissector, as number -> text.
std::map<int, std::string> lua_table(const std::string& lua, const std::string& name) {
  std::smatch m;
  const std::regex table("local " + name + " = \\{([^}]*)\\}");
  if (!std::regex_search(lua, m, table)) return {};
  const std::string body = m[1];
  std::map<int, std::string> out;
  const std::regex entry("\\[(\\d+)\\] = \"([^\"]*)\"");
  for (auto it = std::sregex_iterator(body.begin(), body.end(), entry); it != std::sregex_iterator(); ++it) {
    out[std::stoi((*it)[1])] = (*it)[2];
  }
  return out;
}

// The capture writer's kind numbers come from the registry and the dissector decodes by its own
// table: the two must agree, or existing captures decode as the wrong drive (docs/pcap.md).
TEST(DriveRegistry, TheDissectorsKindsAreTheRegistrysCaptureKinds) {
  std::ifstream in(std::string(IBS_SOURCE_DIR) + "/tools/wireshark/interbus.lua");
  ASSERT_TRUE(in) << "tools/wireshark/interbus.lua";
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string lua = ss.str();
  std::map<int, std::string> expected{{0, "other"}};
  for (const DriveKind& k : drive_kinds()) {
    ASSERT_NE(k.capture, nullptr) << k->name();
    EXPECT_NE(k.capture->kind, 0) << "0 is the format's \"other\"";
    EXPECT_TRUE(expected.emplace(k.capture->kind, std::string(k.capture->label)).second)
        << k->name() << ": kind " << int(k.capture->kind) << " twice";
  }
  EXPECT_EQ(lua_table(lua, "kinds"), expected);
  EXPECT_EQ(find_drive_kind("vf1000")->capture->kind, 1) << "existing captures say 1 for the VF1000";
  EXPECT_EQ(find_drive_kind("mc6000")->capture->kind, 2) << "existing captures say 2 for the MC6000";
  // Every value format a drive declares is one the dissector knows.
  const auto formats = lua_table(lua, "value_formats");
  for (const DriveKind& k : drive_kinds()) {
    for (int ibcnf = 0; ibcnf <= 3; ++ibcnf) {
      DeviceSettings s;
      s.drive.set_integer("ibcnf", ibcnf);
      try {
        (void)k->configure(s);  // the writer asks for the format of configured settings only
      } catch (const SettingsError&) {
        continue;
      }
      const CaptureFormat f = k.capture->format(s);
      EXPECT_TRUE(formats.contains(static_cast<int>(f.values))) << k->name() << " IBCNF " << ibcnf;
    }
  }
  EXPECT_EQ(find_drive_kind("vf1000")->capture->format(DeviceSettings{}).values, CaptureValues::hz_005);
  DeviceSettings q16;
  q16.drive.set_integer("ibcnf", 2);
  EXPECT_EQ(find_drive_kind("mc6000")->capture->format(q16).values, CaptureValues::q16);
}

}  // namespace
}  // namespace ibs::devices
