"""Pure, vectorized physics kernels: arrays in, arrays out. Imports only numpy."""
