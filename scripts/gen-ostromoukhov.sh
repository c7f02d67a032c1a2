#!/usr/bin/env bash
# Regenerates filters/ostromoukhov_table.h from data/ostromoukhov-varcoeff.tsv.
set -euo pipefail
cd "$(dirname "$0")/.."
awk 'BEGIN{print "/* Generated from data/ostromoukhov-varcoeff.tsv (Ostromoukhov, SIGGRAPH 2001, varcoeffED.c v1).\n * Columns: right, down-left, down, sum. Regenerate with scripts/gen-ostromoukhov.sh. */\nstatic const int pnpr_ostromoukhov[256][4] = {"} /^[0-9]/{printf "    {%d, %d, %d, %d},\n",$2,$3,$4,$5} END{print "};"}' \
  data/ostromoukhov-varcoeff.tsv > filters/ostromoukhov_table.h
