// Module terrain: see its headers.
