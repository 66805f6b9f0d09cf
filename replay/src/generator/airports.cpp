// The aerodromes of the global scenario (kew/replay/airports.hpp): the selection is here,
// the figures are the aerodrome table's (data/aerodromes.csv, OurAirports, public domain):
// each aerodrome's position is the mean of its runway thresholds, its elevation the highest
// threshold, as the lower limit of alerting reads them.
//
// The selection: the busiest hubs of every continent; the Arctic fields (Svalbard,
// Pituffik, Alert, Eureka, Resolute, the North Slope, Chukotka) and the Antarctic ones
// whose links cross the polar caps; islands of the Atlantic and the Pacific (the Azores,
// Bermuda, Ascension, Hawaii, Micronesia, Polynesia, Midway, Wake) that put routes over
// open ocean and across the antimeridian. Each is named by its ident in the table, which
// is OurAirports': Lima, Lusaka and Harare under their former indicators. NZSP, the skiway
// at the South Pole, lies 2 km from the pole.
#include "kew/replay/airports.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace kew::replay {
namespace {

using enum Continent;

constexpr SelectedAirport kSelection[] = {
    // Europe
    {"EGLL", Europe},  // London Heathrow
    {"EGCC", Europe},  // Manchester
    {"EGPH", Europe},  // Edinburgh
    {"EIDW", Europe},  // Dublin
    {"EINN", Europe},  // Shannon
    {"LFPG", Europe},  // Paris Charles de Gaulle
    {"LFMN", Europe},  // Nice
    {"EHAM", Europe},  // Amsterdam
    {"EBBR", Europe},  // Brussels
    {"EDDF", Europe},  // Frankfurt
    {"EDDM", Europe},  // Munich
    {"EDDB", Europe},  // Berlin Brandenburg
    {"LSZH", Europe},  // Zurich
    {"LOWW", Europe},  // Vienna
    {"LKPR", Europe},  // Prague
    {"EPWA", Europe},  // Warsaw
    {"LHBP", Europe},  // Budapest
    {"LROP", Europe},  // Bucharest
    {"LGAV", Europe},  // Athens
    {"LIRF", Europe},  // Rome Fiumicino
    {"LIMC", Europe},  // Milan Malpensa
    {"LEMD", Europe},  // Madrid
    {"LEBL", Europe},  // Barcelona
    {"LPPT", Europe},  // Lisbon
    {"LPPD", Europe},  // Ponta Delgada
    {"LPLA", Europe},  // Lajes
    {"EKCH", Europe},  // Copenhagen
    {"ESSA", Europe},  // Stockholm Arlanda
    {"ENGM", Europe},  // Oslo
    {"EFHK", Europe},  // Helsinki
    {"BIKF", Europe},  // Keflavik
    {"ENTC", Europe},  // Tromso
    {"ENKR", Europe},  // Kirkenes
    {"EFRO", Europe},  // Rovaniemi
    {"ENSB", Europe},  // Svalbard Longyearbyen
    {"ULLI", Europe},  // St Petersburg Pulkovo
    {"UUEE", Europe},  // Moscow Sheremetyevo
    {"ULMM", Europe},  // Murmansk
    {"UKBB", Europe},  // Kyiv Boryspil
    {"LTFM", Europe},  // Istanbul
    {"LMML", Europe},  // Malta
    {"LYBE", Europe},  // Belgrade
    {"UMMS", Europe},  // Minsk
    // Africa
    {"FAOR", Africa},  // Johannesburg
    {"FACT", Africa},  // Cape Town
    {"FALE", Africa},  // Durban King Shaka
    {"HECA", Africa},  // Cairo
    {"HAAB", Africa},  // Addis Ababa
    {"HKJK", Africa},  // Nairobi
    {"HTDA", Africa},  // Dar es Salaam
    {"HUEN", Africa},  // Entebbe
    {"DNMM", Africa},  // Lagos
    {"DGAA", Africa},  // Accra
    {"GOBD", Africa},  // Dakar Blaise Diagne
    {"GMMN", Africa},  // Casablanca
    {"DAAG", Africa},  // Algiers
    {"DTTA", Africa},  // Tunis
    {"HSSK", Africa},  // Khartoum
    {"FNLU", Africa},  // Luanda
    {"FZAA", Africa},  // Kinshasa
    {"FMMI", Africa},  // Antananarivo
    {"FIMP", Africa},  // Mauritius
    {"FSIA", Africa},  // Seychelles
    {"FQMA", Africa},  // Maputo
    {"FLLS", Africa},  // Lusaka (FLKK; OurAirports keeps the former indicator)
    {"FVHA", Africa},  // Harare (FVRG; OurAirports keeps the former indicator)
    {"GVAC", Africa},  // Sal
    {"FHAW", Africa},  // Ascension Wideawake
    {"GCLP", Africa},  // Gran Canaria
    // Asia
    {"OMDB", Asia},  // Dubai
    {"OTHH", Asia},  // Doha Hamad
    {"OERK", Asia},  // Riyadh
    {"OEJN", Asia},  // Jeddah
    {"OKKK", Asia},  // Kuwait
    {"OOMS", Asia},  // Muscat
    {"LLBG", Asia},  // Tel Aviv
    {"OJAI", Asia},  // Amman
    {"LCLK", Asia},  // Larnaca
    {"LTAI", Asia},  // Antalya
    {"LTAC", Asia},  // Ankara
    {"OIIE", Asia},  // Tehran Imam Khomeini
    {"OPKC", Asia},  // Karachi
    {"VIDP", Asia},  // Delhi
    {"VABB", Asia},  // Mumbai
    {"VOBL", Asia},  // Bengaluru
    {"VECC", Asia},  // Kolkata
    {"VCBI", Asia},  // Colombo
    {"VRMM", Asia},  // Male
    {"VNKT", Asia},  // Kathmandu
    {"VGHS", Asia},  // Dhaka
    {"VTBS", Asia},  // Bangkok Suvarnabhumi
    {"VVTS", Asia},  // Ho Chi Minh City
    {"VVNB", Asia},  // Hanoi
    {"WSSS", Asia},  // Singapore
    {"WMKK", Asia},  // Kuala Lumpur
    {"WIII", Asia},  // Jakarta
    {"WADD", Asia},  // Bali
    {"RPLL", Asia},  // Manila
    {"VHHH", Asia},  // Hong Kong
    {"RCTP", Asia},  // Taipei Taoyuan
    {"ZBAA", Asia},  // Beijing Capital
    {"ZSPD", Asia},  // Shanghai Pudong
    {"ZGGG", Asia},  // Guangzhou
    {"ZUUU", Asia},  // Chengdu Shuangliu
    {"ZWWW", Asia},  // Urumqi
    {"ZYHB", Asia},  // Harbin
    {"RKSI", Asia},  // Seoul Incheon
    {"RJTT", Asia},  // Tokyo Haneda
    {"RJAA", Asia},  // Tokyo Narita
    {"RJBB", Asia},  // Osaka Kansai
    {"RJCC", Asia},  // Sapporo New Chitose
    {"ROAH", Asia},  // Okinawa Naha
    {"UHHH", Asia},  // Khabarovsk
    {"UHWW", Asia},  // Vladivostok
    {"UHSS", Asia},  // Yuzhno-Sakhalinsk
    {"UHPP", Asia},  // Petropavlovsk-Kamchatsky
    {"UHMM", Asia},  // Magadan
    {"UHMA", Asia},  // Anadyr
    {"UHMD", Asia},  // Provideniya Bay
    {"UHMP", Asia},  // Pevek
    {"UEEE", Asia},  // Yakutsk
    {"UEST", Asia},  // Tiksi
    {"UOOO", Asia},  // Norilsk
    {"UNNT", Asia},  // Novosibirsk
    {"UIII", Asia},  // Irkutsk
    {"USSS", Asia},  // Yekaterinburg
    {"UAAA", Asia},  // Almaty
    {"UTTT", Asia},  // Tashkent
    {"ZMCK", Asia},  // Ulaanbaatar Chinggis Khaan
    // Oceania
    {"YSSY", Oceania},  // Sydney
    {"YMML", Oceania},  // Melbourne
    {"YBBN", Oceania},  // Brisbane
    {"YPPH", Oceania},  // Perth
    {"YPDN", Oceania},  // Darwin
    {"YBCS", Oceania},  // Cairns
    {"YMHB", Oceania},  // Hobart
    {"YSNF", Oceania},  // Norfolk Island
    {"NZAA", Oceania},  // Auckland
    {"NZCH", Oceania},  // Christchurch
    {"NZWN", Oceania},  // Wellington
    {"NZQN", Oceania},  // Queenstown
    {"NZCI", Oceania},  // Chatham Islands
    {"NFFN", Oceania},  // Nadi
    {"NFTF", Oceania},  // Tonga Fua'amotu
    {"NSFA", Oceania},  // Apia Faleolo
    {"NSTU", Oceania},  // Pago Pago
    {"NCRG", Oceania},  // Rarotonga
    {"NTAA", Oceania},  // Tahiti Faa'a
    {"NWWW", Oceania},  // Noumea La Tontouta
    {"NVVV", Oceania},  // Port Vila
    {"AGGH", Oceania},  // Honiara
    {"AYPY", Oceania},  // Port Moresby
    {"PGUM", Oceania},  // Guam
    {"PKMJ", Oceania},  // Majuro
    {"PKWA", Oceania},  // Kwajalein
    {"PTRO", Oceania},  // Palau
    {"PTPN", Oceania},  // Pohnpei
    {"NGTA", Oceania},  // Tarawa Bonriki
    {"PLCH", Oceania},  // Kiritimati
    {"PHNL", Oceania},  // Honolulu
    {"PHOG", Oceania},  // Kahului
    {"PMDY", Oceania},  // Midway
    {"PWAK", Oceania},  // Wake Island
    {"SCIP", Oceania},  // Easter Island Mataveri
    // NorthAmerica
    {"BGSF", NorthAmerica},  // Kangerlussuaq
    {"BGGH", NorthAmerica},  // Nuuk
    {"BGTL", NorthAmerica},  // Pituffik (Thule)
    {"KJFK", NorthAmerica},  // New York JFK
    {"KEWR", NorthAmerica},  // Newark
    {"KBOS", NorthAmerica},  // Boston
    {"KIAD", NorthAmerica},  // Washington Dulles
    {"KATL", NorthAmerica},  // Atlanta
    {"KMIA", NorthAmerica},  // Miami
    {"KORD", NorthAmerica},  // Chicago O'Hare
    {"KDFW", NorthAmerica},  // Dallas Fort Worth
    {"KIAH", NorthAmerica},  // Houston
    {"KDEN", NorthAmerica},  // Denver
    {"KPHX", NorthAmerica},  // Phoenix
    {"KLAS", NorthAmerica},  // Las Vegas
    {"KLAX", NorthAmerica},  // Los Angeles
    {"KSFO", NorthAmerica},  // San Francisco
    {"KSEA", NorthAmerica},  // Seattle
    {"KMSP", NorthAmerica},  // Minneapolis
    {"KSLC", NorthAmerica},  // Salt Lake City
    {"PANC", NorthAmerica},  // Anchorage
    {"PAFA", NorthAmerica},  // Fairbanks
    {"PABR", NorthAmerica},  // Utqiagvik
    {"PASC", NorthAmerica},  // Deadhorse
    {"PAOM", NorthAmerica},  // Nome
    {"PADK", NorthAmerica},  // Adak
    {"PASY", NorthAmerica},  // Shemya Eareckson
    {"CYYZ", NorthAmerica},  // Toronto
    {"CYUL", NorthAmerica},  // Montreal
    {"CYVR", NorthAmerica},  // Vancouver
    {"CYYC", NorthAmerica},  // Calgary
    {"CYEG", NorthAmerica},  // Edmonton
    {"CYHZ", NorthAmerica},  // Halifax
    {"CYYT", NorthAmerica},  // St John's
    {"CYQX", NorthAmerica},  // Gander
    {"CYFB", NorthAmerica},  // Iqaluit
    {"CYRB", NorthAmerica},  // Resolute Bay
    {"CYLT", NorthAmerica},  // Alert
    {"CYEU", NorthAmerica},  // Eureka
    {"CYZF", NorthAmerica},  // Yellowknife
    {"CYXY", NorthAmerica},  // Whitehorse
    {"CYEV", NorthAmerica},  // Inuvik
    {"MMMX", NorthAmerica},  // Mexico City
    {"MMUN", NorthAmerica},  // Cancun
    {"MPTO", NorthAmerica},  // Panama Tocumen
    {"MROC", NorthAmerica},  // San Jose Juan Santamaria
    {"MKJP", NorthAmerica},  // Kingston
    {"MDSD", NorthAmerica},  // Santo Domingo
    {"TJSJ", NorthAmerica},  // San Juan
    {"TBPB", NorthAmerica},  // Barbados
    {"MUHA", NorthAmerica},  // Havana
    {"TXKF", NorthAmerica},  // Bermuda
    {"MYNN", NorthAmerica},  // Nassau
    // SouthAmerica
    {"SBGR", SouthAmerica},  // Sao Paulo Guarulhos
    {"SBGL", SouthAmerica},  // Rio de Janeiro Galeao
    {"SBBR", SouthAmerica},  // Brasilia
    {"SBRF", SouthAmerica},  // Recife
    {"SBEG", SouthAmerica},  // Manaus
    {"SBSV", SouthAmerica},  // Salvador
    {"SAEZ", SouthAmerica},  // Buenos Aires Ezeiza
    {"SAWH", SouthAmerica},  // Ushuaia
    {"SCEL", SouthAmerica},  // Santiago
    {"SCCI", SouthAmerica},  // Punta Arenas
    {"SPIM", SouthAmerica},  // Lima (SPJC; OurAirports keeps the former indicator)
    {"SKBO", SouthAmerica},  // Bogota
    {"SEQM", SouthAmerica},  // Quito
    {"SVMI", SouthAmerica},  // Caracas
    {"SLLP", SouthAmerica},  // La Paz
    {"SUMU", SouthAmerica},  // Montevideo
    {"SOCA", SouthAmerica},  // Cayenne
    {"EGYP", SouthAmerica},  // Mount Pleasant Falklands
    // Antarctica
    {"NZSP", Antarctica},  // Amundsen-Scott South Pole
    {"NZFX", Antarctica},  // McMurdo Phoenix
    {"EGAR", Antarctica},  // Rothera
    {"SCRM", Antarctica},  // Teniente Marsh
    {"SAWB", Antarctica},  // Marambio
};

}  // namespace

std::span<const SelectedAirport> selected_airports() { return kSelection; }

std::vector<Airport> world_airports(const eligibility::AerodromeTable& aerodromes) {
  std::vector<Airport> airports;
  airports.reserve(std::size(kSelection));
  for (const SelectedAirport& selected : kSelection) {
    const eligibility::Aerodrome* a = aerodromes.find(selected.ident);
    if (!a)
      throw std::invalid_argument(
          fmt::format("the aerodrome table has no {}, an aerodrome of the global scenario", selected.ident));
    airports.push_back({selected.ident, a->lat_deg, a->lon_deg, a->elevation_ft, selected.continent});
  }
  return airports;
}

}  // namespace kew::replay
