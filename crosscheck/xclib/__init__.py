"""granwave cross-code validation library (granwave, YADE, LIGGGHTS, LAMMPS).

Modules (each imports only those listed before it, so there is no import cycle):
  codefacts   -- facts of the other codes shared by the laws' mappings (LAMMPS pair-style conventions, Unsupported,
                 axis-aligned walls)
  lawdesc     -- the contact laws' keys, units, ranges and defaults from `granwave laws --json`; where granwave is
  traces      -- case/system reading, trace writing (data/SCHEMA.md §2-3), the layer-stress definition
  linear      -- the linear law of a case in YADE's, LIGGGHTS' and LAMMPS' parameters (one mapping module per law)
  hertz_mindlin_maps -- Hertz-Mindlin's constants in each code's terms (E*, G*, restitution, Tsuji, pair_coeff)
  hertz_mindlin -- the Hertz-Mindlin law of a crystal case in YADE's, LIGGGHTS' and LAMMPS' parameters
  laws        -- the registry of those modules: law_of(contact) (drivers never branch on the law's name)
  driver      -- what the three drivers share: the command line of a deck driver (render, run, convert),
                 running the code, the LAMMPS-family data file and crystal lines, the trace datasets
  bench_packing -- the side-by-side benchmark's decks on a packing file: per-bin numbers, granwave's contact-list
                 rule, the data file with each atom's z-bin, the snapshots that count contacts opening and closing
  impact      -- impact cases (data/SCHEMA.md §7) for the drivers: the bodies, run length, dump reader, trace
  observables -- the crystal trace's observables as granwave lists them (`granwave observables --json`)
  hertz_mindlin_impact -- the Hertz-Mindlin law's impact decks (LAMMPS, LIGGGHTS, YADE)
  dumps       -- LIGGGHTS/LAMMPS text dumps read frame by frame; the dumped forces put back to the step's
  sysbuild    -- a Python builder of system files (test fixtures only; real runs use `granwave build`)
  compare     -- comparison maths (max |diff|/peak, relative L2, measures) on traces
  ruler       -- the one measuring ruler: `granwave analyze --json`, translated
  sweepmath   -- sweep maths and tables (derived cases, peaks at positions, pairwise differences)
  conventions -- the contact-law conventions traces record; differences; granwave's convention twins
  runners     -- running each code in a fresh directory with a timeout; results kept for resuming
  preparation -- one gas (granwave's) prepared at a pressure by granwave, YADE's PeriTriaxController and a LAMMPS
                 servo on fix deform; every packing measured by one reader (`granwave packing`)
  impact_judge -- an impact case's rows: each code against the closed forms, Mindlin's compliance and granwave
  impact_report -- the impact cases' report (impact.md: deviation tables, psi2 table, rows, verdict)
  impact_figures -- the impact cases' figures (Chung & Ooi's panels)
  impactcheck -- `crosscheck run` on impact cases: each code run and measured, then judged, reported, drawn
  sweep_point -- one sweep point: its derived case run by every code through the harness's steps; its pairs
  sweep_judge -- a sweep's pairs of codes over its points against [sweep.<name>]; failed runs
  sweep_report -- a sweep's Markdown (head, verdict, wall times) and JSON
  sweep_plots -- a sweep's figures
  sweep_damping -- `crosscheck sweep damping`: first peaks over gamma_0
  sweep_friction -- `crosscheck sweep friction`: P and S speeds over kt/k
  sweep_rolling -- `crosscheck sweep rolling`: speeds, peaks and the dispersion ridge over k_r/k_t
  sweep       -- `crosscheck sweep`: the command's checks and its three sweeps
  judge       -- one case of `crosscheck run`: every pair of codes' traces and measures against the tolerances
  report      -- `crosscheck run`'s report.md and overlays
  harness     -- `crosscheck run` as a function (check): cases and suites run, measured, judged, reported
  cli         -- the command line `crosscheck run|sweep`
"""
SCHEMA_VERSION = 1
