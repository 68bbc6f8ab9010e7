// Module synth: see its headers.
