# The tests of kew_protocol: kew_protocol_tests (tests/protocol/CMakeLists.txt) and, under
# the sanitizers, kew_decoder_tests (tests/fuzz/CMakeLists.txt) build these.
set(KEW_PROTOCOL_TESTS
  test_aircraft_json.cpp
  test_alert_json.cpp
  test_asterix_cat048.cpp
  test_asterix_golden.cpp
  test_asterix_intent.cpp
  test_asterix_roundtrip.cpp
  test_asterix_stream.cpp
  test_cat004_apw.cpp
  test_cat004_encoder.cpp
  test_cat004_tshark.cpp
  test_formats.cpp
  test_gzip.cpp
  test_json_object_cutter.cpp
  test_modbus_map.cpp
  test_ndjson.cpp
  test_opensky.cpp
  test_opensky_rest.cpp
  test_readsb.cpp
  test_readsb_trace.cpp
  test_sbs.cpp
  test_text_field_rules.cpp
)
list(TRANSFORM KEW_PROTOCOL_TESTS PREPEND ${PROJECT_SOURCE_DIR}/tests/protocol/)
