"""granwave cross-code validation library (YADE, LIGGGHTS, granwave).

Modules:
  traces   -- case/system reading, trace writing (data/SCHEMA.md §2-3), the layer-stress definition
  sysbuild -- a Python builder of system files (test fixtures only; real runs use `granwave build`)
  compare  -- comparison maths (max |diff|/peak, relative L2, measures) on traces
  ruler    -- the one measuring ruler: `granwave analyze --json`, translated
  runners  -- running each code in a fresh directory with a timeout
  report   -- Markdown + PNG report
"""
SCHEMA_VERSION = 1
