"""What shakes the building: response spectra of records and pairs, the code's target spectra
and isolation design quantities, the scaling rules (one module each in rules/, found by its
registry), record pairs scaled to a site's MCE_R at levels of intensity (code suites), records
scaled to a design displacement, and intensity measures. Pure functions over records and
arrays; the engine runs only where a rule needs the building's own response."""
