// Module pipeline: see its headers.
