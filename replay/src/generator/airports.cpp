// The aerodromes of the global scenario (kew/replay/airports.hpp).
//
// Source: aerodrome reference points and elevations as published in the States' AIPs, as
// collected by OurAirports (public domain, https://ourairports.com/data/), rounded to
// 0.0001° (about 10 m) and 1 ft. Every position was checked against OurAirports'
// runways.csv: each lies within 3 km of the centre of its aerodrome's runway thresholds,
// and each elevation within 60 ft of theirs, except SBRF, SBSV and FALE, whose thresholds
// have no coordinates there. OurAirports files Lima, Lusaka, Harare and Kuwait under their
// former indicators (SPIM, FLLS, FVHA, OKBK); the table uses the current ones. NZSP, the
// skiway at the South Pole, is at −90°, 0° as published.
//
// The selection: the busiest hubs of every continent; the Arctic fields (Svalbard,
// Pituffik, Alert, Eureka, Resolute, the North Slope, Chukotka) and the Antarctic ones
// whose links cross the polar caps; islands of the Atlantic and the Pacific (the Azores,
// Bermuda, Ascension, Hawaii, Micronesia, Polynesia, Midway, Wake) that put routes over
// open ocean and across the antimeridian. Longitudes are east positive, so negative in the
// Americas (but Shemya, at the western end of the Aleutians), in the Atlantic west of
// Greenwich and in the Pacific east of the antimeridian (Hawaii, Samoa, Tonga, Tahiti,
// the Chatham Islands, Midway, Provideniya).
#include "kew/replay/airports.hpp"

namespace kew::replay {
namespace {

using enum Continent;

constexpr Airport kAirports[] = {
    // Europe
    {"EGLL", 51.4706, -0.4619, 83, Europe},  // London Heathrow
    {"EGCC", 53.3537, -2.2750, 257, Europe},  // Manchester
    {"EGPH", 55.9500, -3.3725, 135, Europe},  // Edinburgh
    {"EIDW", 53.4213, -6.2701, 242, Europe},  // Dublin
    {"EINN", 52.7020, -8.9248, 46, Europe},  // Shannon
    {"LFPG", 49.0097, 2.5479, 392, Europe},  // Paris Charles de Gaulle
    {"LFMN", 43.6584, 7.2159, 12, Europe},  // Nice
    {"EHAM", 52.3086, 4.7639, -11, Europe},  // Amsterdam
    {"EBBR", 50.9014, 4.4844, 184, Europe},  // Brussels
    {"EDDF", 50.0333, 8.5706, 364, Europe},  // Frankfurt
    {"EDDM", 48.3538, 11.7861, 1487, Europe},  // Munich
    {"EDDB", 52.3514, 13.4939, 157, Europe},  // Berlin Brandenburg
    {"LSZH", 47.4647, 8.5492, 1416, Europe},  // Zurich
    {"LOWW", 48.1103, 16.5697, 600, Europe},  // Vienna
    {"LKPR", 50.1008, 14.2600, 1247, Europe},  // Prague
    {"EPWA", 52.1657, 20.9671, 362, Europe},  // Warsaw
    {"LHBP", 47.4298, 19.2611, 495, Europe},  // Budapest
    {"LROP", 44.5711, 26.0850, 314, Europe},  // Bucharest
    {"LGAV", 37.9364, 23.9445, 308, Europe},  // Athens
    {"LIRF", 41.8003, 12.2389, 13, Europe},  // Rome Fiumicino
    {"LIMC", 45.6306, 8.7231, 768, Europe},  // Milan Malpensa
    {"LEMD", 40.4719, -3.5626, 1998, Europe},  // Madrid
    {"LEBL", 41.2971, 2.0785, 12, Europe},  // Barcelona
    {"LPPT", 38.7813, -9.1359, 374, Europe},  // Lisbon
    {"LPPD", 37.7412, -25.6979, 259, Europe},  // Ponta Delgada
    {"LPLA", 38.7618, -27.0908, 180, Europe},  // Lajes
    {"EKCH", 55.6179, 12.6560, 17, Europe},  // Copenhagen
    {"ESSA", 59.6519, 17.9186, 137, Europe},  // Stockholm Arlanda
    {"ENGM", 60.1939, 11.1004, 681, Europe},  // Oslo
    {"EFHK", 60.3172, 24.9633, 179, Europe},  // Helsinki
    {"BIKF", 63.9850, -22.6056, 171, Europe},  // Keflavik
    {"ENTC", 69.6833, 18.9189, 31, Europe},  // Tromso
    {"ENKR", 69.7258, 29.8913, 283, Europe},  // Kirkenes
    {"EFRO", 66.5648, 25.8304, 642, Europe},  // Rovaniemi
    {"ENSB", 78.2461, 15.4656, 88, Europe},  // Svalbard Longyearbyen
    {"ULLI", 59.8003, 30.2625, 78, Europe},  // St Petersburg Pulkovo
    {"UUEE", 55.9726, 37.4146, 622, Europe},  // Moscow Sheremetyevo
    {"ULMM", 68.7817, 32.7508, 266, Europe},  // Murmansk
    {"UKBB", 50.3450, 30.8947, 427, Europe},  // Kyiv Boryspil
    {"LTFM", 41.2753, 28.7519, 325, Europe},  // Istanbul
    {"LMML", 35.8575, 14.4775, 300, Europe},  // Malta
    {"LYBE", 44.8184, 20.3091, 335, Europe},  // Belgrade
    {"UMMS", 53.8825, 28.0307, 670, Europe},  // Minsk
    // Africa
    {"FAOR", -26.1392, 28.2460, 5558, Africa},  // Johannesburg
    {"FACT", -33.9648, 18.6017, 151, Africa},  // Cape Town
    {"FALE", -29.6144, 31.1197, 295, Africa},  // Durban King Shaka
    {"HECA", 30.1219, 31.4056, 382, Africa},  // Cairo
    {"HAAB", 8.9779, 38.7993, 7625, Africa},  // Addis Ababa
    {"HKJK", -1.3192, 36.9278, 5330, Africa},  // Nairobi
    {"HTDA", -6.8781, 39.2026, 182, Africa},  // Dar es Salaam
    {"HUEN", 0.0424, 32.4435, 3782, Africa},  // Entebbe
    {"DNMM", 6.5774, 3.3212, 135, Africa},  // Lagos
    {"DGAA", 5.6052, -0.1668, 205, Africa},  // Accra
    {"GOBD", 14.6700, -17.0733, 290, Africa},  // Dakar Blaise Diagne
    {"GMMN", 33.3675, -7.5900, 656, Africa},  // Casablanca
    {"DAAG", 36.6910, 3.2154, 82, Africa},  // Algiers
    {"DTTA", 36.8510, 10.2272, 22, Africa},  // Tunis
    {"HSSK", 15.5895, 32.5532, 1265, Africa},  // Khartoum
    {"FNLU", -8.8584, 13.2312, 243, Africa},  // Luanda
    {"FZAA", -4.3858, 15.4446, 1027, Africa},  // Kinshasa
    {"FMMI", -18.7969, 47.4788, 4198, Africa},  // Antananarivo
    {"FIMP", -20.4302, 57.6836, 186, Africa},  // Mauritius
    {"FSIA", -4.6743, 55.5218, 10, Africa},  // Seychelles
    {"FQMA", -25.9208, 32.5726, 145, Africa},  // Maputo
    {"FLKK", -15.3308, 28.4526, 3779, Africa},  // Lusaka
    {"FVRG", -17.9318, 31.0928, 4887, Africa},  // Harare
    {"GVAC", 16.7414, -22.9494, 177, Africa},  // Sal
    {"FHAW", -7.9696, -14.3937, 278, Africa},  // Ascension Wideawake
    {"GCLP", 27.9319, -15.3866, 78, Africa},  // Gran Canaria
    // Asia
    {"OMDB", 25.2528, 55.3644, 62, Asia},  // Dubai
    {"OTHH", 25.2731, 51.6081, 13, Asia},  // Doha Hamad
    {"OERK", 24.9576, 46.6988, 2049, Asia},  // Riyadh
    {"OEJN", 21.6796, 39.1565, 48, Asia},  // Jeddah
    {"OKKK", 29.2266, 47.9689, 206, Asia},  // Kuwait
    {"OOMS", 23.5933, 58.2844, 48, Asia},  // Muscat
    {"LLBG", 32.0114, 34.8867, 135, Asia},  // Tel Aviv
    {"OJAI", 31.7226, 35.9932, 2395, Asia},  // Amman
    {"LCLK", 34.8751, 33.6249, 8, Asia},  // Larnaca
    {"LTAI", 36.8987, 30.8005, 177, Asia},  // Antalya
    {"LTAC", 40.1281, 32.9951, 3125, Asia},  // Ankara
    {"OIIE", 35.4161, 51.1522, 3305, Asia},  // Tehran Imam Khomeini
    {"OPKC", 24.9065, 67.1608, 100, Asia},  // Karachi
    {"VIDP", 28.5665, 77.1031, 777, Asia},  // Delhi
    {"VABB", 19.0887, 72.8679, 39, Asia},  // Mumbai
    {"VOBL", 13.1979, 77.7063, 3000, Asia},  // Bengaluru
    {"VECC", 22.6547, 88.4467, 16, Asia},  // Kolkata
    {"VCBI", 7.1808, 79.8841, 26, Asia},  // Colombo
    {"VRMM", 4.1918, 73.5291, 6, Asia},  // Male
    {"VNKT", 27.6966, 85.3591, 4390, Asia},  // Kathmandu
    {"VGHS", 23.8433, 90.3978, 30, Asia},  // Dhaka
    {"VTBS", 13.6811, 100.7472, 5, Asia},  // Bangkok Suvarnabhumi
    {"VVTS", 10.8188, 106.6520, 33, Asia},  // Ho Chi Minh City
    {"VVNB", 21.2212, 105.8072, 39, Asia},  // Hanoi
    {"WSSS", 1.3502, 103.9944, 22, Asia},  // Singapore
    {"WMKK", 2.7456, 101.7099, 69, Asia},  // Kuala Lumpur
    {"WIII", -6.1256, 106.6559, 34, Asia},  // Jakarta
    {"WADD", -8.7482, 115.1672, 14, Asia},  // Bali
    {"RPLL", 14.5086, 121.0194, 75, Asia},  // Manila
    {"VHHH", 22.3080, 113.9185, 28, Asia},  // Hong Kong
    {"RCTP", 25.0777, 121.2330, 106, Asia},  // Taipei Taoyuan
    {"ZBAA", 40.0801, 116.5846, 116, Asia},  // Beijing Capital
    {"ZSPD", 31.1434, 121.8052, 13, Asia},  // Shanghai Pudong
    {"ZGGG", 23.3924, 113.2988, 50, Asia},  // Guangzhou
    {"ZUUU", 30.5785, 103.9471, 1625, Asia},  // Chengdu Shuangliu
    {"ZWWW", 43.9071, 87.4742, 2125, Asia},  // Urumqi
    {"ZYHB", 45.6234, 126.2503, 457, Asia},  // Harbin
    {"RKSI", 37.4691, 126.4510, 23, Asia},  // Seoul Incheon
    {"RJTT", 35.5523, 139.7800, 35, Asia},  // Tokyo Haneda
    {"RJAA", 35.7647, 140.3864, 141, Asia},  // Tokyo Narita
    {"RJBB", 34.4273, 135.2440, 26, Asia},  // Osaka Kansai
    {"RJCC", 42.7752, 141.6923, 82, Asia},  // Sapporo New Chitose
    {"ROAH", 26.1958, 127.6459, 12, Asia},  // Okinawa Naha
    {"UHHH", 48.5280, 135.1883, 244, Asia},  // Khabarovsk
    {"UHWW", 43.3990, 132.1480, 46, Asia},  // Vladivostok
    {"UHSS", 46.8887, 142.7175, 59, Asia},  // Yuzhno-Sakhalinsk
    {"UHPP", 53.1679, 158.4536, 131, Asia},  // Petropavlovsk-Kamchatsky
    {"UHMM", 59.9110, 150.7206, 574, Asia},  // Magadan
    {"UHMA", 64.7350, 177.7414, 194, Asia},  // Anadyr
    {"UHMD", 64.3781, -173.2433, 72, Asia},  // Provideniya Bay
    {"UHMP", 69.7833, 170.5970, 11, Asia},  // Pevek
    {"UEEE", 62.0933, 129.7706, 325, Asia},  // Yakutsk
    {"UEST", 71.6977, 128.9030, 26, Asia},  // Tiksi
    {"UOOO", 69.3111, 87.3322, 574, Asia},  // Norilsk
    {"UNNT", 55.0126, 82.6507, 365, Asia},  // Novosibirsk
    {"UIII", 52.2680, 104.3890, 1675, Asia},  // Irkutsk
    {"USSS", 56.7431, 60.8027, 764, Asia},  // Yekaterinburg
    {"UAAA", 43.3521, 77.0405, 2234, Asia},  // Almaty
    {"UTTT", 41.2579, 69.2812, 1417, Asia},  // Tashkent
    {"ZMCK", 47.6467, 106.8192, 4482, Asia},  // Ulaanbaatar Chinggis Khaan
    // Oceania
    {"YSSY", -33.9461, 151.1772, 21, Oceania},  // Sydney
    {"YMML", -37.6733, 144.8433, 434, Oceania},  // Melbourne
    {"YBBN", -27.3842, 153.1175, 13, Oceania},  // Brisbane
    {"YPPH", -31.9403, 115.9669, 67, Oceania},  // Perth
    {"YPDN", -12.4147, 130.8769, 103, Oceania},  // Darwin
    {"YBCS", -16.8858, 145.7553, 10, Oceania},  // Cairns
    {"YMHB", -42.8361, 147.5103, 13, Oceania},  // Hobart
    {"YSNF", -29.0416, 167.9387, 371, Oceania},  // Norfolk Island
    {"NZAA", -37.0081, 174.7917, 23, Oceania},  // Auckland
    {"NZCH", -43.4894, 172.5322, 123, Oceania},  // Christchurch
    {"NZWN", -41.3272, 174.8053, 41, Oceania},  // Wellington
    {"NZQN", -45.0211, 168.7392, 1171, Oceania},  // Queenstown
    {"NZCI", -43.8100, -176.4572, 43, Oceania},  // Chatham Islands
    {"NFFN", -17.7554, 177.4431, 59, Oceania},  // Nadi
    {"NFTF", -21.2412, -175.1497, 126, Oceania},  // Tonga Fua'amotu
    {"NSFA", -13.8300, -172.0083, 58, Oceania},  // Apia Faleolo
    {"NSTU", -14.3310, -170.7120, 32, Oceania},  // Pago Pago
    {"NCRG", -21.2027, -159.8057, 19, Oceania},  // Rarotonga
    {"NTAA", -17.5537, -149.6070, 5, Oceania},  // Tahiti Faa'a
    {"NWWW", -22.0146, 166.2130, 52, Oceania},  // Noumea La Tontouta
    {"NVVV", -17.6993, 168.3198, 70, Oceania},  // Port Vila
    {"AGGH", -9.4280, 160.0550, 28, Oceania},  // Honiara
    {"AYPY", -9.4434, 147.2200, 146, Oceania},  // Port Moresby
    {"PGUM", 13.4834, 144.7960, 298, Oceania},  // Guam
    {"PKMJ", 7.0648, 171.2720, 6, Oceania},  // Majuro
    {"PKWA", 8.7202, 167.7320, 9, Oceania},  // Kwajalein
    {"PTRO", 7.3673, 134.5443, 176, Oceania},  // Palau
    {"PTPN", 6.9851, 158.2090, 10, Oceania},  // Pohnpei
    {"NGTA", 1.3816, 173.1470, 9, Oceania},  // Tarawa Bonriki
    {"PLCH", 1.9862, -157.3500, 5, Oceania},  // Kiritimati
    {"PHNL", 21.3187, -157.9224, 13, Oceania},  // Honolulu
    {"PHOG", 20.8986, -156.4305, 54, Oceania},  // Kahului
    {"PMDY", 28.2017, -177.3810, 13, Oceania},  // Midway
    {"PWAK", 19.2821, 166.6360, 14, Oceania},  // Wake Island
    {"SCIP", -27.1648, -109.4219, 227, Oceania},  // Easter Island Mataveri
    // NorthAmerica
    {"BGSF", 67.0122, -50.7116, 165, NorthAmerica},  // Kangerlussuaq
    {"BGGH", 64.1909, -51.6781, 283, NorthAmerica},  // Nuuk
    {"BGTL", 76.5312, -68.7032, 251, NorthAmerica},  // Pituffik (Thule)
    {"KJFK", 40.6398, -73.7789, 13, NorthAmerica},  // New York JFK
    {"KEWR", 40.6925, -74.1687, 18, NorthAmerica},  // Newark
    {"KBOS", 42.3643, -71.0052, 20, NorthAmerica},  // Boston
    {"KIAD", 38.9445, -77.4558, 313, NorthAmerica},  // Washington Dulles
    {"KATL", 33.6367, -84.4281, 1026, NorthAmerica},  // Atlanta
    {"KMIA", 25.7932, -80.2906, 8, NorthAmerica},  // Miami
    {"KORD", 41.9786, -87.9048, 680, NorthAmerica},  // Chicago O'Hare
    {"KDFW", 32.8968, -97.0380, 607, NorthAmerica},  // Dallas Fort Worth
    {"KIAH", 29.9844, -95.3414, 97, NorthAmerica},  // Houston
    {"KDEN", 39.8617, -104.6731, 5434, NorthAmerica},  // Denver
    {"KPHX", 33.4343, -112.0116, 1135, NorthAmerica},  // Phoenix
    {"KLAS", 36.0801, -115.1522, 2181, NorthAmerica},  // Las Vegas
    {"KLAX", 33.9425, -118.4081, 125, NorthAmerica},  // Los Angeles
    {"KSFO", 37.6190, -122.3750, 13, NorthAmerica},  // San Francisco
    {"KSEA", 47.4490, -122.3093, 433, NorthAmerica},  // Seattle
    {"KMSP", 44.8820, -93.2218, 841, NorthAmerica},  // Minneapolis
    {"KSLC", 40.7884, -111.9778, 4227, NorthAmerica},  // Salt Lake City
    {"PANC", 61.1743, -149.9963, 152, NorthAmerica},  // Anchorage
    {"PAFA", 64.8151, -147.8560, 439, NorthAmerica},  // Fairbanks
    {"PABR", 71.2854, -156.7660, 44, NorthAmerica},  // Utqiagvik
    {"PASC", 70.1947, -148.4652, 65, NorthAmerica},  // Deadhorse
    {"PAOM", 64.5122, -165.4453, 37, NorthAmerica},  // Nome
    {"PADK", 51.8780, -176.6460, 18, NorthAmerica},  // Adak
    {"PASY", 52.7123, 174.1136, 95, NorthAmerica},  // Shemya Eareckson
    {"CYYZ", 43.6772, -79.6306, 569, NorthAmerica},  // Toronto
    {"CYUL", 45.4706, -73.7408, 118, NorthAmerica},  // Montreal
    {"CYVR", 49.1939, -123.1844, 14, NorthAmerica},  // Vancouver
    {"CYYC", 51.1139, -114.0203, 3557, NorthAmerica},  // Calgary
    {"CYEG", 53.3097, -113.5800, 2373, NorthAmerica},  // Edmonton
    {"CYHZ", 44.8808, -63.5086, 477, NorthAmerica},  // Halifax
    {"CYYT", 47.6186, -52.7519, 461, NorthAmerica},  // St John's
    {"CYQX", 48.9369, -54.5681, 496, NorthAmerica},  // Gander
    {"CYFB", 63.7564, -68.5558, 110, NorthAmerica},  // Iqaluit
    {"CYRB", 74.7169, -94.9694, 221, NorthAmerica},  // Resolute Bay
    {"CYLT", 82.5178, -62.2806, 100, NorthAmerica},  // Alert
    {"CYEU", 79.9947, -85.8142, 256, NorthAmerica},  // Eureka
    {"CYZF", 62.4628, -114.4403, 675, NorthAmerica},  // Yellowknife
    {"CYXY", 60.7096, -135.0670, 2317, NorthAmerica},  // Whitehorse
    {"CYEV", 68.3042, -133.4829, 224, NorthAmerica},  // Inuvik
    {"MMMX", 19.4363, -99.0721, 7316, NorthAmerica},  // Mexico City
    {"MMUN", 21.0365, -86.8771, 22, NorthAmerica},  // Cancun
    {"MPTO", 9.0714, -79.3835, 135, NorthAmerica},  // Panama Tocumen
    {"MROC", 9.9939, -84.2088, 3021, NorthAmerica},  // San Jose Juan Santamaria
    {"MKJP", 17.9357, -76.7875, 10, NorthAmerica},  // Kingston
    {"MDSD", 18.4297, -69.6689, 59, NorthAmerica},  // Santo Domingo
    {"TJSJ", 18.4394, -66.0018, 9, NorthAmerica},  // San Juan
    {"TBPB", 13.0746, -59.4925, 169, NorthAmerica},  // Barbados
    {"MUHA", 22.9892, -82.4091, 210, NorthAmerica},  // Havana
    {"TXKF", 32.3640, -64.6787, 12, NorthAmerica},  // Bermuda
    {"MYNN", 25.0390, -77.4662, 16, NorthAmerica},  // Nassau
    // SouthAmerica
    {"SBGR", -23.4356, -46.4731, 2459, SouthAmerica},  // Sao Paulo Guarulhos
    {"SBGL", -22.8100, -43.2506, 28, SouthAmerica},  // Rio de Janeiro Galeao
    {"SBBR", -15.8692, -47.9208, 3497, SouthAmerica},  // Brasilia
    {"SBRF", -8.1265, -34.9236, 33, SouthAmerica},  // Recife
    {"SBEG", -3.0386, -60.0497, 264, SouthAmerica},  // Manaus
    {"SBSV", -12.9086, -38.3225, 64, SouthAmerica},  // Salvador
    {"SAEZ", -34.8222, -58.5358, 67, SouthAmerica},  // Buenos Aires Ezeiza
    {"SAWH", -54.8433, -68.2958, 102, SouthAmerica},  // Ushuaia
    {"SCEL", -33.3930, -70.7858, 1555, SouthAmerica},  // Santiago
    {"SCCI", -53.0026, -70.8546, 139, SouthAmerica},  // Punta Arenas
    {"SPJC", -12.0219, -77.1143, 113, SouthAmerica},  // Lima
    {"SKBO", 4.7016, -74.1469, 8361, SouthAmerica},  // Bogota
    {"SEQM", -0.1292, -78.3575, 7841, SouthAmerica},  // Quito
    {"SVMI", 10.6031, -66.9906, 234, SouthAmerica},  // Caracas
    {"SLLP", -16.5133, -68.1923, 13325, SouthAmerica},  // La Paz
    {"SUMU", -34.8384, -56.0308, 105, SouthAmerica},  // Montevideo
    {"SOCA", 4.8198, -52.3604, 26, SouthAmerica},  // Cayenne
    {"EGYP", -51.8228, -58.4472, 244, SouthAmerica},  // Mount Pleasant Falklands
    // Antarctica
    {"NZSP", -90.0000, 0.0000, 9300, Antarctica},  // Amundsen-Scott South Pole
    {"NZFX", -77.9547, 166.7669, 80, Antarctica},  // McMurdo Phoenix
    {"EGAR", -67.5675, -68.1274, 32, Antarctica},  // Rothera
    {"SCRM", -62.1908, -58.9867, 147, Antarctica},  // Teniente Marsh
    {"SAWB", -64.2383, -56.6308, 760, Antarctica},  // Marambio
};

}  // namespace

std::span<const Airport> world_airports() { return kAirports; }

}  // namespace kew::replay
