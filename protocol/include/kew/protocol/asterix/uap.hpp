#pragma once
// The User Application Profiles kew walks, and the field reference numbers (FRN) of the
// items it reads. Item lengths follow the EUROCONTROL specifications (cross-checked with
// the structured definitions of zoranbosnjak/asterix-specs); the UAPs of the editions
// listed are identical, later extension octets being reached through FX.

#include "kew/protocol/asterix/record_walker.hpp"

namespace kew::protocol::asterix {

/// CAT062 SDPS track messages, editions 1.16 to 1.21 (also walks 1.12 records).
const Uap& cat062_uap();
/// CAT048 monoradar target reports, editions 1.15 to 1.32.
const Uap& cat048_uap();
/// CAT021 ADS-B target reports, editions 2.1 to 2.7.
const Uap& cat021_uap();
/// CAT021 ADS-B target reports, edition 0.26 (0.23 to 0.25 differ in items kew reads:
/// I021/130 is 6 bytes there; not supported).
const Uap& cat021_v026_uap();

namespace cat062 {
inline constexpr unsigned kDataSource = 1;        // I062/010
inline constexpr unsigned kTimeOfTrack = 4;       // I062/070
inline constexpr unsigned kPositionWgs84 = 5;     // I062/105
inline constexpr unsigned kPositionCartesian = 6; // I062/100
inline constexpr unsigned kVelocity = 7;          // I062/185
inline constexpr unsigned kMode3A = 9;            // I062/060
inline constexpr unsigned kTargetId = 10;         // I062/245
inline constexpr unsigned kAircraftDerived = 11;  // I062/380
inline constexpr unsigned kTrackNumber = 12;      // I062/040
inline constexpr unsigned kTrackStatus = 13;      // I062/080
inline constexpr unsigned kMeasuredFl = 17;       // I062/136
inline constexpr unsigned kGeometricAlt = 18;     // I062/130
inline constexpr unsigned kBarometricAlt = 19;    // I062/135
inline constexpr unsigned kRateOfClimb = 20;      // I062/220
inline constexpr unsigned kFlightPlan = 21;       // I062/390
// Subfields (0-based) of I062/380 and I062/390.
inline constexpr unsigned k380Address = 0;
inline constexpr unsigned k380Identification = 1;
inline constexpr unsigned k380SelectedAltitude = 5;       // SAL
inline constexpr unsigned k380FinalSelectedAltitude = 6;  // FSS
inline constexpr unsigned k380TrackAngleRate = 15;        // TAR
inline constexpr unsigned k390Callsign = 1;
}  // namespace cat062

namespace cat048 {
inline constexpr unsigned kDataSource = 1;        // I048/010
inline constexpr unsigned kTimeOfDay = 2;         // I048/140
inline constexpr unsigned kDescriptor = 3;        // I048/020
inline constexpr unsigned kPolarPosition = 4;     // I048/040
inline constexpr unsigned kMode3A = 5;            // I048/070
inline constexpr unsigned kFlightLevel = 6;       // I048/090
inline constexpr unsigned kAddress = 8;           // I048/220
inline constexpr unsigned kIdentification = 9;    // I048/240
inline constexpr unsigned kModeSMbData = 10;      // I048/250
inline constexpr unsigned kTrackNumber = 11;      // I048/161
inline constexpr unsigned kVelocity = 13;         // I048/200
inline constexpr unsigned kTrackStatus = 14;      // I048/170
inline constexpr unsigned kCommsCapability = 21;  // I048/230
}  // namespace cat048

namespace cat021 {
// Editions 2.x.
inline constexpr unsigned kDataSource = 1;        // I021/010
inline constexpr unsigned kDescriptor = 2;        // I021/040
inline constexpr unsigned kTimeOfPosition = 5;    // I021/071
inline constexpr unsigned kPosition = 6;          // I021/130
inline constexpr unsigned kPositionHighRes = 7;   // I021/131
inline constexpr unsigned kAddress = 11;          // I021/080
inline constexpr unsigned kTimeOfPositionRx = 12; // I021/073
inline constexpr unsigned kTimeOfVelocityRx = 14; // I021/075
inline constexpr unsigned kGeometricHeight = 16;  // I021/140
inline constexpr unsigned kMode3A = 19;           // I021/070
inline constexpr unsigned kFlightLevel = 21;      // I021/145
inline constexpr unsigned kBaroVerticalRate = 24; // I021/155
inline constexpr unsigned kGeoVerticalRate = 25;  // I021/157
inline constexpr unsigned kGroundVector = 26;     // I021/160
inline constexpr unsigned kTrackAngleRate = 27;   // I021/165
inline constexpr unsigned kTimeOfTransmission = 28;  // I021/077
inline constexpr unsigned kIdentification = 29;   // I021/170
inline constexpr unsigned kSelectedAltitude = 32; // I021/146
inline constexpr unsigned kFinalSelectedAltitude = 33;  // I021/148
}  // namespace cat021

namespace cat021_v026 {
inline constexpr unsigned kDataSource = 1;        // I021/010
inline constexpr unsigned kDescriptor = 2;        // I021/040 (2 bytes)
inline constexpr unsigned kTimeOfDay = 3;         // I021/030
inline constexpr unsigned kPosition = 4;          // I021/130 (8 bytes)
inline constexpr unsigned kAddress = 5;           // I021/080
inline constexpr unsigned kGeometricAltitude = 6; // I021/140
inline constexpr unsigned kFlightLevel = 10;      // I021/145
inline constexpr unsigned kBaroVerticalRate = 14; // I021/155
inline constexpr unsigned kGeoVerticalRate = 15;  // I021/157
inline constexpr unsigned kGroundVector = 16;     // I021/160
inline constexpr unsigned kRateOfTurn = 17;       // I021/165 (extended: TI, then ROT)
inline constexpr unsigned kIdentification = 18;   // I021/170
inline constexpr unsigned kSelectedAltitude = 24; // I021/146 Intermediate State Selected Altitude
inline constexpr unsigned kFinalSelectedAltitude = 25;  // I021/148
inline constexpr unsigned kMode3A = 27;           // I021/070
}  // namespace cat021_v026

}  // namespace kew::protocol::asterix
