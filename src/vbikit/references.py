"""Bibliography of vbikit: every model, preset, parameter source and verification reference.

One registry, ``REFERENCES``, keyed by a short citation key.  ``docs/references.md`` and
``docs/references.bib`` are generated from it (``python docs/scripts/generate.py``; a test
fails when they differ), and ``MODEL_REFERENCES`` says which entries a model relies on,
so that ``vbikit cite SCENARIO`` and ``vbikit run --json`` can list them.

To add a source: add a ``Reference`` to ``REFERENCES``, name its key in
``MODEL_REFERENCES`` for the models that use it (tire models: in the class's ``references``),
and regenerate the docs.
"""
from __future__ import annotations

from dataclasses import dataclass, field


@dataclass(frozen=True)
class Reference:
    """One bibliographic entry (the fields of a BibTeX entry).

    ``kind`` is the BibTeX entry type (article, book, manual, software, misc); ``authors`` are
    "Family, Given" strings; ``used_for`` says in a sentence what vbikit takes from it.
    """

    key: str
    kind: str
    title: str
    year: str
    used_for: str
    authors: tuple[str, ...] = ()
    journal: str = ""
    volume: str = ""
    number: str = ""
    pages: str = ""
    publisher: str = ""
    address: str = ""
    edition: str = ""
    doi: str = ""
    isbn: str = ""
    url: str = ""
    note: str = ""
    organization: str = ""
    #: False while a DOI (or other locator) is written from secondary citation data and not yet
    #: checked against the publisher; docs/references.md marks such entries
    checked: bool = True
    #: how the entry was checked, or what was searched without confirming it (docs/references.md
    #: prints it); every entry with a DOI says one or the other
    verification: str = ""
    extra: dict[str, str] = field(default_factory=dict)

    def text(self) -> str:
        """A one-line citation: authors (year) title. Journal volume(number), pages. DOI."""
        who = "; ".join(self.authors) or self.organization
        parts = [f"{who} ({self.year}). {self.title}." if who else f"{self.title} ({self.year})."]
        if self.journal:
            vol = self.volume + (f"({self.number})" if self.number else "")
            venue = ", ".join(p for p in (self.journal, vol, self.pages) if p)
        else:
            venue = ", ".join(p for p in (f"{self.edition} ed." if self.edition else "", self.publisher, self.address) if p)
        if venue:
            parts.append(venue + ".")
        if self.doi:
            parts.append(f"doi:{self.doi}" + ("" if self.checked else " (not yet checked against the publisher)"))
        if self.isbn:
            parts.append(f"ISBN {self.isbn}.")
        if self.url:
            parts.append(self.url)
        if self.note:
            parts.append(f"({self.note}.)")
        return " ".join(parts)

    def bibtex(self) -> str:
        """The entry as BibTeX."""
        fields = {
            "author": " and ".join(self.authors),
            "title": "{" + self.title + "}",
            "journal": self.journal,
            "year": self.year,
            "volume": self.volume,
            "number": self.number,
            "pages": self.pages.replace("–", "--"),
            "publisher": self.publisher,
            "address": self.address,
            "edition": self.edition,
            "organization": self.organization,
            "doi": self.doi,
            "isbn": self.isbn,
            "url": self.url,
            "note": self.note,
            **self.extra,
        }
        body = ",\n".join(f"  {k} = {{{v}}}" for k, v in fields.items() if v)
        return f"@{self.kind}{{{self.key},\n{body}\n}}"


_R = Reference

#: where the entries marked unconfirmed were searched (no general network: no direct Crossref query)
SEARCHED = "the project's search of stored public web pages and documentation pages (2026-12-02)"

#: Every source vbikit relies on, by citation key.
REFERENCES: dict[str, Reference] = {r.key: r for r in (
    # Title only: searched in public repositories (README/bib citations), indexed web pages, issue
    # trackers and documentation for the exact title, the DOI-less phrase "multi-point tire model" and
    # the field test (HS20-44, Cypress Bayou, LSU/Southern University authors); no record of the
    # article was found, so authors, journal, year and DOI stay empty until read from the publisher.
    _R("MultiPointTire", "article", "A Multi-Point Tire Model for Studying Bridge–Vehicle Coupled Vibration", "n.d.",
       "the programme vbikit implements: the coupled equations (Eqs. 1–9), the multi-point tire (Eq. 6), "
       "the random road (Eq. 7), the HS20-44 truck (Table 1), the three paper bridges, the studies of "
       "Figs. 5–11 and the Cypress Bayou field test; equation, table and figure numbers in the docs refer to it",
       note="The copy vbikit follows prints neither authors, journal nor year; complete this entry from the "
            "published article",
       verification="Unconfirmed. The copy vbikit follows gives on its first page only the title, the abstract and "
                    "the keywords (dynamic impact factor; single-point tire model; multi-point tire model; disk "
                    "model; field test), no authors, journal, volume, year or DOI. Searched for the exact title, and "
                    "for it with 'Deng', 'Cai', 'Cypress Bayou' and 'International Journal of Structural Stability "
                    "and Dynamics', in " + SEARCHED + ": no record of the article"),
    # DOI 10.1680/vosasuml.35393 (ICE Virtual Library) not found in any publisher or indexing record
    # searched; the book data (3rd ed., Thomas Telford 1999; 1st ed. Noordhoff 1972) agree with
    # reference lists of citing papers (secondary).  Stays unchecked.
    _R("Fryba1999", "book", "Vibration of Solids and Structures under Moving Loads", "1999",
       "moving-force solution of the simply supported beam and its dynamic amplification table "
       "(verification: docs/verification.md)",
       authors=("Frýba, Ladislav",), publisher="Thomas Telford", address="London", edition="3rd",
       isbn="0-7277-2741-9", checked=False, doi="10.1680/vosasuml.35393", note="First edition Noordhoff, Groningen, 1972",
       verification="DOI unconfirmed: searched for it and for title, publisher and year in " + SEARCHED + "; the "
                    "book data (3rd ed., Thomas Telford, London, 1999) agree with reference lists of citing papers, "
                    "no publisher or Crossref record of the DOI was found"),
    _R("YangYau1997", "article", "Vehicle-bridge interaction element for dynamic analysis", "1997",
       "sprung mass on a simply supported beam: midspan and vehicle peaks (verification)",
       authors=("Yang, Yeong-Bin", "Yau, Jong-Dar"), journal="Journal of Structural Engineering (ASCE)",
       volume="123", number="11", pages="1512–1518", doi="10.1061/(ASCE)0733-9445(1997)123:11(1512)", checked=False,
       verification="DOI unconfirmed: searched for it and for title, authors, volume and pages in " + SEARCHED +
                    "; no publisher (ASCE Library) or Crossref record found. The DOI has ASCE's form for "
                    "J. Struct. Eng. 123(11), p. 1512"),
    _R("Biggs1964", "book", "Introduction to Structural Dynamics", "1964",
       "sprung + unsprung mass on a beam, first mode (closed-form verification of a two-mass vehicle, §8.5)",
       authors=("Biggs, John M.",), publisher="McGraw-Hill", address="New York", isbn="0-07-005255-7"),
    _R("ISO8608", "manual", "Mechanical vibration — Road surface profiles — Reporting of measured data (ISO 8608)", "2016",
       "road roughness classes A–H as displacement PSD Gd(n0) at n0 = 0.1 cycle/m, exponent 2",
       organization="International Organization for Standardization", address="Geneva", edition="2nd"),
    _R("HuangWangShahawy1992", "article", "Impact analysis of continuous multigirder bridges due to moving vehicles", "1992",
       "the road PSD form φ(n) = φ(n0)(n/n0)^−2 that the paper adopts ('the PSD function used by Huang and Wang')",
       authors=("Huang, Dongzhou", "Wang, Ton-Lo", "Shahawy, Mohsen"),
       journal="Journal of Structural Engineering (ASCE)", volume="118", number="12", pages="3427–3443",
       doi="10.1061/(ASCE)0733-9445(1992)118:12(3427)", checked=False,
       verification="DOI unconfirmed: searched for it and for title, authors, volume and pages in " + SEARCHED +
                    "; no publisher or Crossref record found (only the authors' related 1993 report)"),
    _R("WangHuang1992", "article", "Cable-stayed bridge vibration due to road surface roughness", "1992",
       "the random-road representation as a sum of cosines with random phases (the form of the paper's Eq. 7)",
       authors=("Wang, Ton-Lo", "Huang, Dongzhou"), journal="Journal of Structural Engineering (ASCE)",
       volume="118", number="5", pages="1354–1374", doi="10.1061/(ASCE)0733-9445(1992)118:5(1354)", checked=False,
       verification="DOI unconfirmed: searched for it and for title, authors, volume and pages in " + SEARCHED +
                    "; no publisher or Crossref record found"),
    # No publisher (World Scientific) or indexing record of this article was found in the searched
    # corpora; volume, issue, pages and DOI 10.1142/S0219455410003609 stay as written, unchecked.
    _R("Yin2010", "article", "Bridge vibration under vehicular loads: tire patch contact versus point contact", "2010",
       "the deformable-disk tire the paper compares with (vbikit's disk tire is a documented substitute after it)",
       authors=("Yin, Xinfeng", "Cai, C. S.", "Fang, Zhi", "Deng, Lu"),
       journal="International Journal of Structural Stability and Dynamics", volume="10", number="3",
       pages="529–554", checked=False, doi="10.1142/S0219455410003609",
       verification="DOI unconfirmed: searched for it and for title, authors, journal, volume and pages in "
                    + SEARCHED + "; no publisher (World Scientific) or Crossref record found"),
    # No publisher (Elsevier) or indexing record of this article was found in the searched corpora;
    # volume, issue, pages and DOI 10.1016/j.jsv.2011.05.012 stay as written, unchecked.
    _R("Chang2011", "article", "Disk model for wheels moving over highway bridges with rough surfaces", "2011",
       "the rigid-disk tire (the wheel follows the envelope of the surface)",
       authors=("Chang, K. C.", "Wu, F. B.", "Yang, Y. B."), journal="Journal of Sound and Vibration",
       volume="330", number="20", pages="4930–4944", checked=False, doi="10.1016/j.jsv.2011.05.012",
       verification="DOI unconfirmed: searched for it and for title, authors, journal, volume and pages in "
                    + SEARCHED + "; no publisher (Elsevier) or Crossref record found"),
    _R("AASHTO-LRFD", "manual", "AASHTO LRFD Bridge Design Specifications", "2020",
       "dynamic load allowance IM = 0.33 / 0.15 fatigue / 0.75 deck joints (Table 3.6.2.1-1); tire contact "
       "area 0.508 m × 0.254 m (3.6.1.2.5), the multi-point tire's default contact length; fatigue resistance "
       "N = A·Δf⁻³ and thresholds (ΔF)_TH of categories A–E′ (6.6.1.2.5, Tables 6.6.1.2.5-1 and -3)",
       organization="American Association of State Highway and Transportation Officials", address="Washington, DC",
       edition="9th"),
    _R("AASHTO-Standard2002", "manual", "Standard Specifications for Highway Bridges", "2002",
       "the HS20-44 design truck (3.7) and the impact fraction I = 50/(L + 125) ≤ 0.30, L in ft (3.8.2.1)",
       organization="American Association of State Highway and Transportation Officials", address="Washington, DC",
       edition="17th"),
    _R("PCI-BDM", "manual", "PCI Bridge Design Manual", "2011",
       "section properties of the AASHTO Type I–VI prestressed I-girders (the girders of the slab-on-girder presets)",
       organization="Precast/Prestressed Concrete Institute", address="Chicago", edition="3rd"),
    _R("Hambly1991", "book", "Bridge Deck Behaviour", "1991",
       "grillage idealisation of slab-on-girder decks (member properties, slab torsion split between the two "
       "directions) and the oblique (skew) mesh of skew decks",
       authors=("Hambly, Edmund C.",), publisher="E & FN Spon", address="London", edition="2nd"),
    _R("JTG-D60-2015", "manual", "General Specifications for Design of Highway Bridges and Culverts (JTG D60-2015)", "2015",
       "impact coefficient μ as a function of the first bending frequency (§4.3.2), a reference line on IM plots",
       organization="Ministry of Transport of the People's Republic of China", address="Beijing"),
    _R("CSA-S6-2019", "manual", "Canadian Highway Bridge Design Code (CSA S6:19)", "2019",
       "dynamic load allowance by the number of axles governing (3.8.4.5.3), a design-code line beside the IM",
       organization="CSA Group", address="Toronto"),
    _R("OHBDC1983", "manual", "Ontario Highway Bridge Design Code", "1983",
       "dynamic amplification as a function of the first flexural frequency, a design-code line beside the IM",
       organization="Ontario Ministry of Transportation and Communications", address="Downsview, Ontario", edition="2nd"),
    _R("LLAnalyzer", "software", "LL Analyzer: live load analysis of continuous beams under the CL-625 truck", "n.d.",
       "second source for the CSA S6 dynamic load allowance by the axles that govern (0.40 one axle, 0.30 two "
       "axles or axles 1–3, 0.25 other groups of three or more), as it implements them for the CL-625 truck",
       organization="GitHub user sumonrh", url="https://github.com/sumonrh/ll-analyzer",
       note="README, section 'Analysis Rules and Accuracy', and src/beam-engine.ts, function truckGroupDla, read "
            "at commit 04e7d3c; the same rule (an automatic DLA of 40, 30 or 25 per cent by the selected axles) in the "
            "release notes of OpenSees Studio 1.0.14 (github.com/sumonrh/OpenSeesStudio). Neither names the CSA S6 "
            "edition or clause"),
    _R("IxiawenJTG", "misc", "Worked answer: impact coefficient of a 30 m simply supported T-girder highway bridge "
       "with a fundamental frequency of 4.5 Hz (question 26692305)", "n.d.",
       "second source for the JTG D60 impact coefficient μ = 0.1767 ln f − 0.0157 (1.5 ≤ f ≤ 14 Hz); "
       "worked value μ(4.5 Hz) = 0.25",
       organization="app.ixiawen.com question bank",
       url="https://app.ixiawen.com/question/26692305/4ee8f276ad20abb8d4b8c099ae5a33d2.html",
       note="In Chinese; the answer cites JTG D60-2004 §4.3.2 item 5, p. 26. The same question and answer at "
            "ti.zuoweng.com/ti/eVANKKKQ (2019-12-17); other answers of the bank (e.g. question 1579277) quote the "
            "formula with the same clause"),
    # Checked against the publisher's Crossref deposit, openjournals/joss-papers
    # joss.04404/10.21105.joss.04404.crossref.xml (commit 3ba445ae): title, authors J. W. Ngan and
    # C. C. Caprani, JOSS volume 7, issue 76, article 4404, published 2022-08-30,
    # DOI 10.21105/joss.04404.  Sources disagree on the issue only: the ospgrillage README/PyPI
    # "please cite" text and one stored version of the paper's JATS file give 7(77), another JATS
    # version gives 76.  Issue 76 is the deposit's, and JOSS's monthly numbering agrees (its deposit
    # for joss.04405 has issue 85 = May 2023, so issue 76 = August 2022).
    _R("Ngan2022", "article", "ospgrillage: A bridge deck grillage analysis preprocessor for OpenSeesPy", "2022",
       "ospgrillage, whose live OpenSees models the mode import is tested on (tests/verification/test_ospgrillage_import.py), "
       "and its meshing rules for skew decks (oblique mesh up to 30°, orthogonal above 11°; the skew above which "
       "vbikit warns)",
       authors=("Ngan, J. W.", "Caprani, Colin C."), journal="Journal of Open Source Software", volume="7",
       number="76", pages="4404", doi="10.21105/joss.04404",
       verification="Checked against the publisher's Crossref deposit (JOSS papers repository, "
                    "joss.04404/10.21105.joss.04404.crossref.xml): title, authors, volume 7, issue 76, article 4404, "
                    "published 2022-08-30, DOI 10.21105/joss.04404",
       url="https://pypi.org/project/ospgrillage/",
       note="Issue 76 as in the publisher's Crossref deposit, published 30 August 2022; the package's "
            "README cites it as 7(77)"),
    # Journal, volume 85, issue EM3 (July 1959) and pages 67–94 agree with a scan of the article itself
    # (library copy with its cover sheet, scribd document 489002686).  The DOI 10.1061/JMCEA3.0000098
    # appears only in secondary sources (many public repositories, links to ascelibrary.org/doi/...),
    # not in a publisher record read here: stays unchecked.
    _R("Newmark1959", "article", "A method of computation for structural dynamics", "1959",
       "the Newmark average-acceleration integrator (crossing.integrator = \"newmark\")",
       authors=("Newmark, Nathan M.",), journal="Journal of the Engineering Mechanics Division (ASCE)", volume="85",
       number="EM3", pages="67–94", checked=False, doi="10.1061/JMCEA3.0000098",
       verification="Journal, volume 85, issue EM3 (July 1959) and pages 67–94 agree with a scan of the article "
                    "(library copy). DOI unconfirmed: searched for it in " + SEARCHED + "; it appears only in "
                    "secondary sources, not in a publisher or Crossref record"),
    _R("NigamJennings1969", "article", "Calculation of response spectra from strong-motion earthquake records", "1969",
       "the exact step of a damped modal oscillator under a load linear over the step (exact modal stepping)",
       authors=("Nigam, Navin C.", "Jennings, Paul C."), journal="Bulletin of the Seismological Society of America",
       volume="59", number="2", pages="909–922", doi="10.1785/BSSA0590020909", checked=False,
       verification="Journal, volume 59, number 2, pages 909–922 (April 1969), title and authors agree with a "
                    "scan of the article's first page, found when its title was searched in " + SEARCHED + ". DOI unconfirmed: no publisher "
                    "(SSA/GeoScienceWorld) or Crossref record of it was found; it has the SSA form for BSSA 59(2), "
                    "p. 909"),
    _R("Chopra2017", "book", "Dynamics of Structures: Theory and Applications to Earthquake Engineering", "2017",
       "modal superposition, Rayleigh/modal damping and the piecewise-exact step (§5.2)",
       authors=("Chopra, Anil K.",), publisher="Pearson", address="Hoboken, NJ", edition="5th", isbn="978-0-13-455512-6"),
    _R("Blevins1979", "book", "Formulas for Natural Frequency and Mode Shape", "1979",
       "natural frequencies of simply supported and continuous beams (verification)",
       authors=("Blevins, Robert D.",), publisher="Van Nostrand Reinhold", address="New York",
       isbn="0-442-20710-7", note="Reprinted by Krieger, Malabar, FL, 2001"),
    # Title, SoftwareX, volume 26, article 101725 (2024) agree with a citation in a public repository's
    # README (secondary); the VBI-2D repository's README and user guide (version of 3 February 2026,
    # read at commit 1d36c83) do not cite the article.  No publisher record of the DOI was found:
    # stays unchecked.
    _R("Cantero2024", "article", "VBI-2D – Road vehicle-bridge interaction simulation tool and verification framework for Matlab",
       "2024", "independent vehicle–bridge code the beam crossings are checked against (verification)",
       authors=("Cantero, Daniel",), journal="SoftwareX", volume="26", pages="101725",
       checked=False, doi="10.1016/j.softx.2024.101725", url="https://github.com/DanielCanteroNTNU/VBI-2D",
       verification="DOI unconfirmed: searched for it and for title, journal and article number in " + SEARCHED +
                    "; no publisher (Elsevier) or Crossref record found; title, SoftwareX 26, 101725 (2024) "
                    "agree with a citation in a public repository's README (secondary)"),
    _R("McKenna2010", "article", "Nonlinear finite-element analysis software architecture using object composition", "2010",
       "OpenSees, the independent grillage and moving-load cross-check of the slab-on-girder deck (verification)",
       authors=("McKenna, Frank", "Scott, Michael H.", "Fenves, Gregory L."),
       journal="Journal of Computing in Civil Engineering", volume="24", number="1", pages="95–107",
       doi="10.1061/(ASCE)CP.1943-5487.0000002", checked=False,
       verification="DOI unconfirmed: searched for it and for title, authors and journal in " + SEARCHED +
                    "; no publisher (ASCE Library) or Crossref record found"),
    _R("Zhu2018", "article", "OpenSeesPy: Python library for the OpenSees finite element framework", "2018",
       "the Python interface to OpenSees used by the cross-check tests",
       authors=("Zhu, Minjie", "McKenna, Frank", "Scott, Michael H."), journal="SoftwareX", volume="7",
       pages="6–11", doi="10.1016/j.softx.2017.10.009", checked=False,
       verification="DOI unconfirmed: searched for it and for title, journal, volume and pages in " + SEARCHED +
                    "; the OpenSeesPy documentation found does not give it; no publisher (Elsevier) or Crossref "
                    "record found"),
    _R("pycba", "software", "pycba: Python Continuous Beam Analysis", "2024",
       "independent static moments, shears and reactions of beams (verification of the static reference)",
       authors=("Caprani, Colin C.",), url="https://github.com/ccaprani/pycba"),
    # Title and Table 7 ("Roughness coefficient for different surface conditions": very good 0–2,
    # good 2–8, average 8–32, poor 32–128 × 1e-6) read on the publisher's page
    # preview.hindawi.com/journals/ace/2022/9946957/tab7.  The DOI is formed from that article number
    # and not shown on the page read: unchecked.  Authors not found.
    _R("AdvCivEng2022", "article",
       "Study on the Technical Status of Old Concrete Truss-Arch Bridge Based on Vehicle-Bridge Interaction", "2022",
       "supports reading the paper's good / average / poor as ISO 8608 classes B / C / D "
       "(its limits 2–8, 8–32, 32–128 × 1e-6 m³ are ISO's Φ(Ω0) class limits)",
       journal="Advances in Civil Engineering", volume="2022", pages="9946957", doi="10.1155/2022/9946957",
       checked=False,
       verification="Title and Table 7 read on the publisher's (Hindawi) page of article 9946957. DOI unconfirmed: "
                    "formed from that article number, not shown on the page read; searched for it and for the title "
                    "in " + SEARCHED + ": no Crossref record found",
       note="Cited only for its Table 7, 'Roughness coefficient for different surface conditions'; "
            "authors to be completed from the publisher's page"),
    # --- fatigue and extremes (vbikit.fatigue, vbikit.extremes)
    # The rainflow example history and counts were checked against two copies quoting the standard
    # (the rainflow package's issue #4 and MathWorks' rainflow page); AASHTO's A and (ΔF)_TH against
    # AISC 360 Appendix 3 Table A-3.1 (same constants; steelcalculator.app reference page and a copy
    # of the table with the SI thresholds 165/110/69/48 MPa); the EN 1993-1-9 knees (N_C 2e6, N_D 5e6,
    # N_L 1e8, m 3 and 5) against Altair's HyperLife Eurocode 3 parameter page.
    _R("ASTM-E1049", "manual", "Standard Practices for Cycle Counting in Fatigue Analysis (ASTM E1049-85, reapproved 2011)",
       "1985",
       "rainflow counting (5.4.4) and its worked example (reversals −2, 1, −3, 5, −1, 3, −4, 4, −2), the test "
       "of vbikit.fatigue.rainflow",
       organization="ASTM International", address="West Conshohocken, PA"),
    _R("EN1993-1-9", "manual", "Eurocode 3: Design of steel structures — Part 1-9: Fatigue (EN 1993-1-9:2005)", "2005",
       "direct-stress S-N curves of the detail categories (7.1, Fig. 7.1: N_C = 2·10⁶, m = 3 to N_D = 5·10⁶, "
       "m = 5 to the cut-off N_L = 10⁸), the partial factor γ_Mf (Table 3.1) and Miner's rule (Annex A)",
       organization="European Committee for Standardization (CEN)", address="Brussels"),
    _R("AISC360-2022", "manual", "Specification for Structural Steel Buildings (ANSI/AISC 360-22)", "2022",
       "second source for the AASHTO detail-category constants A and thresholds (ΔF)_TH (Appendix 3, Table A-3.1 "
       "gives the same values for categories A–E′)",
       organization="American Institute of Steel Construction", address="Chicago"),
    _R("EN1991-2", "manual", "Eurocode 1: Actions on structures — Part 2: Traffic loads on bridges (EN 1991-2:2003)",
       "2003",
       "the return period of about 1000 years of the characteristic road traffic values (the 'eurocode-1000' "
       "preset of vbikit.extremes); railway: HSLM-A/B (Annex E, Table E.1, Figures E.1, E.2), damping "
       "(Table 6.6, Eq. 6.13), resonance speeds and the dynamic analysis (6.4.6), Φ2/Φ3 (6.4.5.2), LM71 (6.3.2), "
       "φ'' (Annex C)",
       organization="European Committee for Standardization (CEN)", address="Brussels",
       note="The wording of the probability of exceedance (10 % in 100 years, or 5 % in 50 years; both about "
            "1000 years) was not confirmed against the standard's text"),
    _R("EN1990", "manual", "Eurocode: Basis of structural design (EN 1990:2002)", "2002",
       "the 100-year design working life of bridges (Table 2.1, category 5; the '100-year' preset)",
       organization="European Committee for Standardization (CEN)", address="Brussels"),
    _R("Nowak1999", "manual", "Calibration of LRFD Bridge Design Code (NCHRP Report 368)", "1999",
       "the 75-year maximum load effect to which the AASHTO LRFD live load is calibrated (the 'aashto-75' preset)",
       authors=("Nowak, Andrzej S.",), organization="Transportation Research Board", address="Washington, DC"),
    _R("Coles2001", "book", "An Introduction to Statistical Modeling of Extreme Values", "2001",
       "GEV and Gumbel block-maximum models (eqs. 3.2–3.5), the GPD of threshold excesses (eq. 4.2), return "
       "levels (eqs. 3.4 and 4.13), maximum likelihood with the observed information and the delta method "
       "(§2.6.4, §3.3.3): vbikit.extremes",
       authors=("Coles, Stuart",), publisher="Springer", address="London", isbn="1-85233-459-2",
       note="Springer Series in Statistics"),
    _R("Gringorten1963", "article", "A plotting rule for extreme probability paper", "1963",
       "the plotting positions p = (i − 0.44)/(n + 0.12) of the Gumbel plot",
       authors=("Gringorten, Irving I.",), journal="Journal of Geophysical Research", volume="68", number="3",
       pages="813–814"),
    _R("rainflow-py", "software", "rainflow: Python implementation of the ASTM E1049-85 rainflow cycle counting algorithm",
       "2024", "whole-history rainflow counting (version 3.2.0) in vbikit.fatigue.rainflow and the reference count "
       "of the chunked-counting tests",
       authors=("Janiszewski, Piotr",), url="https://github.com/iamlikeme/rainflow"),
    _R("pyextremes", "software", "pyextremes: Extreme Value Analysis in Python", "2024",
       "peer check (version 2.6.1) of vbikit.extremes' return levels of block maxima and of peaks over a "
       "threshold (vbikit.extremes fits with scipy.stats directly)",
       authors=("Bocharov, George",), url="https://github.com/georgebv/pyextremes"),
    # --- rail-vehicles (vbikit.vehicle.rail_car, vbikit.road.track)
    _R("Zhai2020", "book", "Vehicle–Track Coupled Dynamics: Theory and Applications", "2020",
       "the planar car model (body, bogies, wheelsets), the linearised Hertz wheel–rail stiffness "
       "k_H = 3/(2G) P0^(1/3) with G = 4.57 R^-0.149 × 1e-8 (conical) / 3.86 R^-0.115 × 1e-8 (worn) m/N^(2/3), "
       "and the German high-speed track spectra's constants",
       authors=("Zhai, Wanming",), publisher="Springer", address="Singapore",
       note="Chapters on the vehicle model, wheel/rail normal contact and track irregularity spectra; "
            "section numbers as cited in the code not yet checked against the printed book"),
    _R("ZhaiWangCai2009", "article", "Fundamentals of vehicle–track coupled dynamics", "2009",
       "the 'China Star' power-car preset (masses, inertias, suspensions, geometry)",
       authors=("Zhai, Wanming", "Wang, Kaiyun", "Cai, Chengbiao"), journal="Vehicle System Dynamics",
       volume="47", number="11", pages="1349–1376",
       note="Values read through their transcription in TTB-2D (TrainProp_ChineseStarPowerCar.m), "
            "per-side stiffnesses and dampings doubled for the planar model"),
    _R("Goicolea2014", "misc", "Simplified Mechanical Description of AVE S-103 - ICE3 Velaro E High Speed Train",
       "2014", "the ICE3 / AVE S-103 intermediate-coach preset (coaches 2, 3, 6, 7)",
       authors=("Goicolea, José M.",), organization="Universidad Politécnica de Madrid",
       url="https://oa.upm.es/43946/1/aves103_ice3.pdf",
       note="Values read through their transcription in TTB-2D (TrainProp_AVE_S103_ICE3_Velaro_E_C2367.m)"),
    _R("Iwnicki1998", "article", "Manchester Benchmarks for Rail Vehicle Simulation", "1998",
       "the Manchester benchmark vehicle preset",
       authors=("Iwnicki, Simon",), journal="Vehicle System Dynamics", volume="30", number="3-4", pages="295–313",
       doi="10.1080/00423119808969454", checked=False,
       verification="DOI unconfirmed: taken from the TTB-2D source file that cites the article "
                    "(TrainProp_Manchester_BenchMark.m); searched for it and for the title in " + SEARCHED +
                    ": no publisher (Taylor & Francis) or Crossref record found"),
    _R("Cantero2022", "article", "TTB-2D: Train-Track-Bridge interaction simulation tool for Matlab", "2022",
       "independent open code read (not copied) for the rail-car presets' source values and the track spectra's "
       "constants (second source)",
       authors=("Cantero, Daniel",), journal="SoftwareX", volume="20", pages="101253",
       doi="10.1016/j.softx.2022.101253", url="https://github.com/DanielCanteroNTNU/TTB-2D", checked=False,
       verification="DOI unconfirmed: taken from the TTB-2D source files' citation notice; searched for it in "
                    + SEARCHED + ": no publisher (Elsevier) or Crossref record found"),
    _R("GuoXia2012", "article",
       "Integral model for train-track-bridge interaction on the Sesia viaduct: Dynamic simulation and critical assessment",
       "2012", "second source of the German high-speed (low disturbance) spectrum's constants "
       "A_v = 4.032e-7 m·rad, Ω_c = 0.8246 rad/m, Ω_r = 0.0206 rad/m",
       authors=("Guo, W. W.", "Xia, H.", "De Roeck, G.", "Liu, K."), journal="Computers & Structures",
       volume="112–113", pages="205–216", doi="10.1016/j.compstruc.2012.09.001", checked=False,
       verification="DOI unconfirmed: taken from the TTB-2D option file that cites the article (A04_Options.m); "
                    "searched for it in " + SEARCHED + ": no publisher (Elsevier) or Crossref record found"),
    _R("GargDukkipati1984", "book", "Dynamics of Railway Vehicle Systems", "1984",
       "the FRA track classes' vertical-profile spectrum S = k A_v Ω_c² / (Ω² (Ω² + Ω_c²)), k = 0.25, "
       "Ω_c = 0.8245 rad/m, A_v = 1.2107 … 0.0339 cm²·rad/m for classes 1–6",
       authors=("Garg, Vijay K.", "Dukkipati, Rao V."), publisher="Academic Press", address="Toronto",
       note="After the US Federal Railroad Administration's track-geometry analyses (Hamid & Yang 1981); "
            "constants checked against two independent open codes (TTB-2D A04_Options.m, after Berawi's thesis; "
            "a public Python vehicle–bridge script); section not yet checked against the printed book"),
    _R("HamidYang1981", "article", "Analytical description of track-geometry variations", "1981",
       "origin of the FRA track-class spectra (as cited by Garg & Dukkipati 1984)",
       authors=("Hamid, A.", "Yang, T.-L."), journal="Transportation Research Record", volume="838", pages="19–26",
       note="Cited through secondary sources; not read"),
    _R("Johnson1985", "book", "Contact Mechanics", "1985",
       "the classical Hertz compliance δ = (9P²/(16E*²R))^(1/3) the empirical wheel–rail constant G is checked against",
       authors=("Johnson, K. L.",), publisher="Cambridge University Press", address="Cambridge"),
    # --- driveby
    _R("YangLinYau2004", "article", "Extracting bridge frequencies from the dynamic response of a passing vehicle", "2004",
       "drive-by frequencies: vehicle, driving (n v / L) and shifted bridge frequencies ω_b ± πv/L of a light sprung mass",
       authors=("Yang, Y. B.", "Lin, C. W.", "Yau, J. D."), journal="Journal of Sound and Vibration", volume="272",
       pages="471–493", note="Bibliographic data from secondary citations; not checked against the paper"),
    _R("YangLin2005", "article", "Vehicle–bridge interaction dynamics and potential applications", "2005",
       "closed form of a light sprung mass over a simply supported beam (verification of the drive-by simulation)",
       authors=("Yang, Y. B.", "Lin, C. W."), journal="Journal of Sound and Vibration", volume="284", pages="205–226",
       note="Bibliographic data from secondary citations; not checked against the paper; the closed form used is "
            "derived in tests/driveby from the paper's stated assumptions"),
    _R("YangZhengZhangXu2018", "article",
       "Inversion of bridge modal shapes and damping from the contact-point response of a test vehicle", "2018",
       "contact-point response u_c = u_v + m_v ü_v / k_v of a single-axle test vehicle",
       authors=("Yang, Y. B.", "Zheng, Y.", "Zhang, B.", "Xu, H."),
       note="Title, venue and pages not confirmed (searched the stored pages corpus for authors, year and title "
            "words without finding the paper)"),
    _R("YangLiChang2014", "article", "Constructing the mode shapes of a bridge from a passing vehicle: a theoretical study",
       "2014", "mode-shape squares from the Hilbert envelope of the band-passed vehicle response",
       authors=("Yang, Y. B.", "Li, Y. C.", "Chang, K. C."), journal="Smart Structures and Systems", volume="13",
       number="5", pages="797–819", note="Bibliographic data from secondary citations; not checked against the paper"),
    _R("Malekjafarian2015", "article", "A review of indirect bridge monitoring using passing vehicles", "2015",
       "review of drive-by (indirect) bridge monitoring", authors=("Malekjafarian, A.", "McGetrick, P. J.", "OBrien, E. J."),
       journal="Shock and Vibration", volume="2015", pages="286139"),
    _R("CanteroHesterBrownjohn2017", "article",
       "Evolution of bridge frequencies and modes of vibration during truck passage", "2017",
       "how bridge frequencies shift with the vehicle's position and mass (limits of drive-by identification)",
       authors=("Cantero, Daniel", "Hester, David", "Brownjohn, James"), journal="Engineering Structures", volume="152",
       pages="452–464"),
    _R("AllemangBrown1982", "inproceedings", "A correlation coefficient for modal vector analysis", "1982",
       "modal assurance criterion (MAC) between healthy and damaged mode-shape estimates",
       authors=("Allemang, R. J.", "Brown, D. L."), publisher="Proceedings of the 1st International Modal Analysis Conference",
       pages="110–116"),
    _R("PandeyBiswasSamman1991", "article", "Damage detection from changes in curvature mode shapes", "1991",
       "curvature-change damage indicator", authors=("Pandey, A. K.", "Biswas, M.", "Samman, M. M."),
       journal="Journal of Sound and Vibration", volume="145", number="2", pages="321–332"),
    # --- rail
    _R("EN1990-A2", "manual", "Eurocode: Basis of structural design — Annex A2: Application for bridges (EN 1990:2002/A1:2005)",
       "2005", "peak deck acceleration limits and the frequency range of the dynamic analysis (A2.4.4.2.1)",
       organization="CEN", address="Brussels"),
    _R("SincBridgeDynamics", "software", "SincBridgeDynamics.jl", "n.d.",
       "second source of the HSLM-A axle lists (TRAIN_MODELS) and of the Table 6.6 damping rule (ec1damping)",
       url="https://github.com/antonioaro/SincBridgeDynamics.jl"),
    _R("YangYauHsu1997", "article", "Vibration of simple beams due to trains moving at high speeds", "1997",
       "resonance and cancellation of equally spaced moving loads on a simple beam (verification)",
       authors=("Yang, Y. B.", "Yau, J. D.", "Hsu, L. C."), journal="Engineering Structures", volume="19", number="11"),
    # --- lifetime
    _R("Caprani2012ADR", "article", "Assessment dynamic ratio for traffic loading on highway bridges", "2012",
       "the assessment dynamic ratio ADR = characteristic total / characteristic static load effect (vbikit.lifetime)",
       authors=("Caprani, Colin C.", "González, Arturo", "Rattigan, Peter H.", "OBrien, Eugene J."),
       journal="Structure and Infrastructure Engineering",
       note="Venue as cited in the literature; volume and pages not checked against the publisher"),
    _R("OBrien2010CDI", "article", "Characteristic dynamic increment for extreme traffic loading events on short and "
       "medium span highway bridges", "2010",
       "the dynamic increment of characteristic (not single-event) load effects (vbikit.lifetime)",
       authors=("OBrien, Eugene J.", "Cantero, Daniel", "Enright, Bernard", "González, Arturo", "Žnidarič, Aleš",
                "Caprani, Colin C."), journal="Engineering Structures", volume="32", number="12",
       note="As cited in the literature; not checked against the publisher"),
    _R("DempsterLairdRubin1977", "article", "Maximum likelihood from incomplete data via the EM algorithm", "1977",
       "the EM fit of the normal mixtures of gross vehicle weight (vbikit.lifetime.traffic)",
       authors=("Dempster, Arthur P.", "Laird, Nan M.", "Rubin, Donald B."),
       journal="Journal of the Royal Statistical Society, Series B", volume="39", number="1", pages="1–38"),
    _R("pybtls", "software", "PyBTLS: Python Bridge Traffic Load Simulation (version 1.0.1)", "2023",
       "the peer of the static lifetime extremes (tests/lifetime/test_peer_pybtls.py) and the multimodal-normal GVW "
       "model", authors=("Caprani, Colin C.", "Zhou, Ziyi", "Rizqiansyah, Akbar"), url="https://pypi.org/project/pybtls/"),
)}

#: Which entries each model relies on, by the names used in scenario files
#: (``"<section>:<model>"``; ``"*"`` entries apply to every crossing).  Tire models declare
#: theirs on the class (``TireModel.references``, :data:`vbikit.contact.TIRE_MODELS`).
MODEL_REFERENCES: dict[str, tuple[str, ...]] = {
    "*": ("MultiPointTire",),
    "bridge:beam": ("Fryba1999",),
    "bridge:slab-on-girder": ("PCI-BDM", "Hambly1991"),
    "bridge:paper-bridge-1": ("MultiPointTire", "PCI-BDM", "Hambly1991"),
    "bridge:paper-bridge-2": ("MultiPointTire", "PCI-BDM", "Hambly1991"),
    "bridge:paper-bridge-3": ("MultiPointTire", "PCI-BDM", "Hambly1991"),
    "bridge:cypress-bayou": ("MultiPointTire", "PCI-BDM", "Hambly1991"),
    "bridge:paper-bridge-1-beam": ("PCI-BDM",),
    "bridge:paper-bridge-2-beam": ("PCI-BDM",),
    "bridge:paper-bridge-3-beam": ("PCI-BDM",),
    "vehicle:moving-force": ("Fryba1999",),
    "vehicle:sprung-mass": ("YangYau1997",),
    "vehicle:quarter-car": ("Biggs1964",),
    "vehicle:hs20-44": ("MultiPointTire", "AASHTO-Standard2002"),
    "vehicle:two-axle": ("AASHTO-Standard2002",),
    "vehicle:dump-truck": ("MultiPointTire",),
    "road:iso": ("ISO8608", "HuangWangShahawy1992", "WangHuang1992"),
    "road:paper-class": ("ISO8608", "AdvCivEng2022"),
    "road:psd": ("HuangWangShahawy1992", "WangHuang1992"),
    "integrator:rk4": ("MultiPointTire",),
    "integrator:newmark": ("Newmark1959",),
    "integrator:exact": ("NigamJennings1969", "Chopra2017"),
    "impact:code-lines": ("AASHTO-LRFD", "AASHTO-Standard2002", "CSA-S6-2019", "OHBDC1983", "JTG-D60-2015",
                          "LLAnalyzer", "IxiawenJTG"),
    "bridge:continuous-beam": ("Blevins1979", "pycba"),
    "vehicle:3s2": ("Cantero2024",),
    "vehicle:axles": ("AASHTO-Standard2002",),
    # --- fatigue and extremes
    "fatigue:rainflow": ("ASTM-E1049", "rainflow-py"),
    "fatigue:en1993": ("EN1993-1-9",),
    "fatigue:aashto": ("AASHTO-LRFD", "AISC360-2022"),
    "extremes:fits": ("Coles2001", "Gringorten1963", "pyextremes"),
    "extremes:return-periods": ("Nowak1999", "EN1990", "EN1991-2"),
    "vehicle:rail-car": ("Zhai2020", "ZhaiWangCai2009", "Goicolea2014", "Iwnicki1998", "Cantero2022"),
    "road:track": ("Zhai2020", "GuoXia2012", "GargDukkipati1984", "HamidYang1981"),
    "driveby:identification": ("YangLinYau2004", "YangLin2005", "Malekjafarian2015", "CanteroHesterBrownjohn2017"),
    "driveby:contact-point": ("YangZhengZhangXu2018",),
    "driveby:mode-shapes": ("YangLiChang2014",),
    "driveby:damage": ("AllemangBrown1982", "PandeyBiswasSamman1991"),
    # --- rail
    **{f"vehicle:hslm-a{k}": ("EN1991-2", "SincBridgeDynamics") for k in range(1, 11)},
    "vehicle:ice3": ("Goicolea2014", "Cantero2022"),
    "rail:checks": ("EN1991-2", "EN1990-A2", "Fryba1999", "NigamJennings1969"),
    # --- lifetime
    "lifetime:adr": ("Caprani2012ADR", "OBrien2010CDI"),
    "lifetime:traffic": ("DempsterLairdRubin1977", "pybtls"),
}


def references_for(models: list[str]) -> list[Reference]:
    """The entries for ``models`` (``"<section>:<model>"`` names of ``MODEL_REFERENCES``) in
    first-use order, without repeats; unknown names contribute nothing."""
    keys: list[str] = []
    for name in ("*", *models):
        for key in MODEL_REFERENCES.get(name, ()):
            if key not in keys:
                keys.append(key)
    return [REFERENCES[k] for k in keys]


def bibtex(entries: list[Reference] | None = None) -> str:
    """BibTeX of ``entries`` (default: all of ``REFERENCES``)."""
    entries = list(REFERENCES.values()) if entries is None else entries
    return "\n\n".join(r.bibtex() for r in entries) + "\n"
