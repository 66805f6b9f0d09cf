// Item formats of every FRN of the UAPs kew walks. Items kew does not read are listed
// too: a record can only be walked past an item whose length is known.
// Sources: EUROCONTROL ASTERIX Part 9 (CAT062), Part 4 (CAT048), Part 12 (CAT021);
// lengths cross-checked against zoranbosnjak/asterix-specs (specs/cat062/cat-1.16..1.21,
// cat048/cat-1.27..1.32, cat021/cat-2.1..2.7 and cat-0.26).

#include <array>

#include "kew/protocol/asterix/uap.hpp"

namespace kew::protocol::asterix {

namespace {

constexpr ItemFormat kSpare = undefined_item();

// ---- CAT062 -------------------------------------------------------------------------
// I062/380 Aircraft Derived Data: ADR ID MHG IAS TAS SAL FSS | TIS TID COM SAB ACS BVR GVR
// | RAN TAR TAN GSP VUN MET EMC | POS GAL PUN MB IAR MAC BPS.
constexpr std::array k062_380{
    fixed(3), fixed(6), fixed(2), fixed(2), fixed(2), fixed(2), fixed(2),
    extended(), repetitive(15), fixed(2), fixed(2), fixed(7), fixed(2), fixed(2),
    fixed(2), fixed(2), fixed(2), fixed(2), fixed(1), fixed(8), fixed(1),
    fixed(6), fixed(2), fixed(1), repetitive(8), fixed(2), fixed(2), fixed(2)};
// I062/290 System Track Update Ages: TRK PSR SSR MDS ADS ES VDL | UAT LOP MLT.
constexpr std::array k062_290{fixed(1), fixed(1), fixed(1), fixed(1), fixed(2),
                              fixed(1), fixed(1), fixed(1), fixed(1), fixed(1)};
// I062/295 Track Data Ages: 31 one-byte ages.
constexpr std::array<ItemFormat, 31> k062_295 = [] {
  std::array<ItemFormat, 31> ages{};
  for (auto& age : ages) age = fixed(1);
  return ages;
}();
// I062/390 Flight Plan Related Data: TAG CSN IFI FCT TAC WTC DEP | DST RDS CFL CTL TOD AST
// STS | STD STA PEM PEC.
constexpr std::array k062_390{
    fixed(2), fixed(7), fixed(4), fixed(1), fixed(4), fixed(1), fixed(4),
    fixed(4), fixed(3), fixed(2), fixed(2), repetitive(4), fixed(6), fixed(1),
    fixed(7), fixed(7), fixed(2), fixed(7)};
// I062/110 Mode 5 Data: SUM PMN POS GA EM1 TOS XP.
constexpr std::array k062_110{fixed(1), fixed(4), fixed(6), fixed(2),
                              fixed(2), fixed(1), fixed(1)};
// I062/500 Estimated Accuracies: APC COV APW AGA ABA ATV AA | ARC.
constexpr std::array k062_500{fixed(4), fixed(2), fixed(4), fixed(1),
                              fixed(1), fixed(2), fixed(2), fixed(1)};
// I062/340 Measured Information: SID POS HEI MDC MDA TYP.
constexpr std::array k062_340{fixed(2), fixed(4), fixed(2), fixed(2), fixed(2), fixed(1)};

constexpr std::array k062{
    fixed(2),             // 1  I062/010 Data Source Identifier
    kSpare,               // 2  spare
    fixed(1),             // 3  I062/015 Service Identification
    fixed(3),             // 4  I062/070 Time Of Track Information
    fixed(8),             // 5  I062/105 Calculated Position WGS-84
    fixed(6),             // 6  I062/100 Calculated Position Cartesian
    fixed(4),             // 7  I062/185 Calculated Velocity Cartesian
    fixed(2),             // 8  I062/210 Calculated Acceleration
    fixed(2),             // 9  I062/060 Track Mode 3/A Code
    fixed(7),             // 10 I062/245 Target Identification
    compound(k062_380),   // 11 I062/380 Aircraft Derived Data
    fixed(2),             // 12 I062/040 Track Number
    extended(),           // 13 I062/080 Track Status
    compound(k062_290),   // 14 I062/290 System Track Update Ages
    fixed(1),             // 15 I062/200 Mode of Movement
    compound(k062_295),   // 16 I062/295 Track Data Ages
    fixed(2),             // 17 I062/136 Measured Flight Level
    fixed(2),             // 18 I062/130 Calculated Geometric Altitude
    fixed(2),             // 19 I062/135 Calculated Barometric Altitude
    fixed(2),             // 20 I062/220 Calculated Rate of Climb/Descent
    compound(k062_390),   // 21 I062/390 Flight Plan Related Data
    extended(),           // 22 I062/270 Target Size and Orientation
    fixed(1),             // 23 I062/300 Vehicle Fleet Identification
    compound(k062_110),   // 24 I062/110 Mode 5 Data and Extended Mode 1 Code
    fixed(2),             // 25 I062/120 Track Mode 2 Code
    extended(3, 3),       // 26 I062/510 Composed Track Number (3-byte parts, FX)
    compound(k062_500),   // 27 I062/500 Estimated Accuracies
    compound(k062_340),   // 28 I062/340 Measured Information
    kSpare, kSpare, kSpare, kSpare, kSpare,  // 29-33 spare
    explicit_length(),    // 34 RE Reserved Expansion Field
    explicit_length(),    // 35 SP Special Purpose Field
};

// ---- CAT048 -------------------------------------------------------------------------
// I048/130 Radar Plot Characteristics: SRL SRR SAM PRL PAM RPD APD.
constexpr std::array k048_130{fixed(1), fixed(1), fixed(1), fixed(1),
                              fixed(1), fixed(1), fixed(1)};
// I048/120 Radial Doppler Speed: CAL, RDS (repetitive, 6-byte elements).
constexpr std::array k048_120{fixed(2), repetitive(6)};

constexpr std::array k048{
    fixed(2),             // 1  I048/010 Data Source Identifier
    fixed(3),             // 2  I048/140 Time-of-Day
    extended(),           // 3  I048/020 Target Report Descriptor
    fixed(4),             // 4  I048/040 Measured Position in Polar Co-ordinates
    fixed(2),             // 5  I048/070 Mode-3/A Code
    fixed(2),             // 6  I048/090 Flight Level
    compound(k048_130),   // 7  I048/130 Radar Plot Characteristics
    fixed(3),             // 8  I048/220 Aircraft Address
    fixed(6),             // 9  I048/240 Aircraft Identification
    repetitive(8),        // 10 I048/250 Mode S MB Data
    fixed(2),             // 11 I048/161 Track Number
    fixed(4),             // 12 I048/042 Calculated Position in Cartesian Co-ordinates
    fixed(4),             // 13 I048/200 Calculated Track Velocity in Polar Co-ordinates
    extended(),           // 14 I048/170 Track Status
    fixed(4),             // 15 I048/210 Track Quality
    extended(),           // 16 I048/030 Warning/Error Conditions (FX-repetitive)
    fixed(2),             // 17 I048/080 Mode-3/A Code Confidence Indicator
    fixed(4),             // 18 I048/100 Mode-C Code and Confidence Indicator
    fixed(2),             // 19 I048/110 Height Measured by 3D Radar
    compound(k048_120),   // 20 I048/120 Radial Doppler Speed
    fixed(2),             // 21 I048/230 Communications/ACAS Capability and Flight Status
    fixed(7),             // 22 I048/260 ACAS Resolution Advisory Report
    fixed(1),             // 23 I048/055 Mode-1 Code
    fixed(2),             // 24 I048/050 Mode-2 Code
    fixed(1),             // 25 I048/065 Mode-1 Code Confidence Indicator
    fixed(2),             // 26 I048/060 Mode-2 Code Confidence Indicator
    explicit_length(),    // 27 SP Special Purpose Field
    explicit_length(),    // 28 RE Reserved Expansion Field
};

// ---- CAT021 (editions 2.x) ------------------------------------------------------------
// I021/220 Met Information: WS WD TMP TRB.
constexpr std::array k021_220{fixed(2), fixed(2), fixed(2), fixed(1)};
// I021/110 Trajectory Intent: TIS (extended), TID (repetitive, 15-byte elements).
constexpr std::array k021_110{extended(), repetitive(15)};
// I021/295 Data Ages: 23 one-byte ages.
constexpr std::array<ItemFormat, 23> k021_295 = [] {
  std::array<ItemFormat, 23> ages{};
  for (auto& age : ages) age = fixed(1);
  return ages;
}();

constexpr std::array k021{
    fixed(2),             // 1  I021/010 Data Source Identification
    extended(),           // 2  I021/040 Target Report Descriptor
    fixed(2),             // 3  I021/161 Track Number
    fixed(1),             // 4  I021/015 Service Identification
    fixed(3),             // 5  I021/071 Time of Applicability for Position
    fixed(6),             // 6  I021/130 Position in WGS-84 Co-ordinates
    fixed(8),             // 7  I021/131 High-Resolution Position in WGS-84
    fixed(3),             // 8  I021/072 Time of Applicability for Velocity
    fixed(2),             // 9  I021/150 Air Speed
    fixed(2),             // 10 I021/151 True Air Speed
    fixed(3),             // 11 I021/080 Target Address
    fixed(3),             // 12 I021/073 Time of Message Reception for Position
    fixed(4),             // 13 I021/074 Time of Message Reception of Position-High Precision
    fixed(3),             // 14 I021/075 Time of Message Reception for Velocity
    fixed(4),             // 15 I021/076 Time of Message Reception of Velocity-High Precision
    fixed(2),             // 16 I021/140 Geometric Height
    extended(),           // 17 I021/090 Quality Indicators
    fixed(1),             // 18 I021/210 MOPS Version
    fixed(2),             // 19 I021/070 Mode 3/A Code
    fixed(2),             // 20 I021/230 Roll Angle
    fixed(2),             // 21 I021/145 Flight Level
    fixed(2),             // 22 I021/152 Magnetic Heading
    fixed(1),             // 23 I021/200 Target Status
    fixed(2),             // 24 I021/155 Barometric Vertical Rate
    fixed(2),             // 25 I021/157 Geometric Vertical Rate
    fixed(4),             // 26 I021/160 Airborne Ground Vector
    fixed(2),             // 27 I021/165 Track Angle Rate
    fixed(3),             // 28 I021/077 Time of ASTERIX Report Transmission
    fixed(6),             // 29 I021/170 Target Identification
    fixed(1),             // 30 I021/020 Emitter Category
    compound(k021_220),   // 31 I021/220 Met Information
    fixed(2),             // 32 I021/146 Selected Altitude
    fixed(2),             // 33 I021/148 Final State Selected Altitude
    compound(k021_110),   // 34 I021/110 Trajectory Intent
    fixed(1),             // 35 I021/016 Service Management
    fixed(1),             // 36 I021/008 Aircraft Operational Status
    // 37 I021/271 Surface Capabilities: in edition 2.1 the second octet has no FX bit
    // (its last bit is data), from 2.2 it has one that is always 0: stop after two.
    extended(1, 1, 2),
    fixed(1),             // 38 I021/132 Message Amplitude
    repetitive(8),        // 39 I021/250 Mode S MB Data
    fixed(7),             // 40 I021/260 ACAS Resolution Advisory Report
    fixed(1),             // 41 I021/400 Receiver ID
    compound(k021_295),   // 42 I021/295 Data Ages
    kSpare, kSpare, kSpare, kSpare, kSpare,  // 43-47 spare
    explicit_length(),    // 48 RE Reserved Expansion Field
    explicit_length(),    // 49 SP Special Purpose Field
};

// ---- CAT021 edition 0.26 ------------------------------------------------------------
constexpr std::array k021_v026{
    fixed(2),             // 1  I021/010 Data Source Identification
    fixed(2),             // 2  I021/040 Target Report Descriptor
    fixed(3),             // 3  I021/030 Time of Day
    fixed(8),             // 4  I021/130 Position in WGS-84 Co-ordinates
    fixed(3),             // 5  I021/080 Target Address
    fixed(2),             // 6  I021/140 Geometric Altitude
    fixed(2),             // 7  I021/090 Figure of Merit
    fixed(1),             // 8  I021/210 Link Technology Indicator
    fixed(2),             // 9  I021/230 Roll Angle
    fixed(2),             // 10 I021/145 Flight Level
    fixed(2),             // 11 I021/150 Air Speed
    fixed(2),             // 12 I021/151 True Air Speed
    fixed(2),             // 13 I021/152 Magnetic Heading
    fixed(2),             // 14 I021/155 Barometric Vertical Rate
    fixed(2),             // 15 I021/157 Geometric Vertical Rate
    fixed(4),             // 16 I021/160 Ground Vector
    extended(),           // 17 I021/165 Rate Of Turn
    fixed(6),             // 18 I021/170 Target Identification
    fixed(1),             // 19 I021/095 Velocity Accuracy
    fixed(1),             // 20 I021/032 Time of Day Accuracy
    fixed(1),             // 21 I021/200 Target Status
    fixed(1),             // 22 I021/020 Emitter Category
    compound(k021_220),   // 23 I021/220 Met Information
    fixed(2),             // 24 I021/146 Intermediate State Selected Altitude
    fixed(2),             // 25 I021/148 Final State Selected Altitude
    compound(k021_110),   // 26 I021/110 Trajectory Intent
    fixed(2),             // 27 I021/070 Mode 3/A Code
    fixed(1),             // 28 I021/131 Signal Amplitude
    kSpare, kSpare, kSpare, kSpare, kSpare,  // 29-33 spare
    explicit_length(),    // 34 RE Reserved Expansion Field
    explicit_length(),    // 35 SP Special Purpose Field
};

}  // namespace

const Uap& cat062_uap() {
  static const Uap uap{k062};
  return uap;
}
const Uap& cat048_uap() {
  static const Uap uap{k048};
  return uap;
}
const Uap& cat021_uap() {
  static const Uap uap{k021};
  return uap;
}
const Uap& cat021_v026_uap() {
  static const Uap uap{k021_v026};
  return uap;
}

}  // namespace kew::protocol::asterix
