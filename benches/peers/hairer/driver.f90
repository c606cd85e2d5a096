! Harness for Hairer's RADAU5 and DOP853 (radau5.f, dop853.f, hinit.f, dc_decsol.f, decsol.f of
! cpmech/hwode, which this repository does not hold: benches/peers/hairer/run.sh builds them beside
! this file). It solves the peer problems of reports/performance.md with the right-hand sides of
! src/perf.rs and prints one JSON object per tolerance: the counts and the median time of the
! solves.
!
! usage: driver METHOD PROBLEM T_END REPEATS TOL...
!   METHOD   radau5 | dop853
!   PROBLEM  cone | pendulum | hertz
!   T_END    end time (the pendulum's comes from `impact bench pendulum`)
!   TOL      the internal tolerance (rtol = atol) wanted; RADAU5 is given (10 tol)^(3/2), which
!            it maps back to tol, and UROUND = 1e-18 when that input is below its floor of
!            10 UROUND, with the Newton tolerance fixed at the value UROUND = 1e-16 gives
module problems
  implicit none
  integer :: which = 0
  double precision, parameter :: tau = 0.3d0, rho = 0.5d0, sigma = 1d-6
end module problems

subroutine fcn(n, x, y, f, rpar, ipar)
  use problems
  implicit none
  integer :: n, ipar(*)
  double precision :: x, y(n), f(n), rpar(*), z, r2
  select case (which)
  case (1)
    z = max(y(1), 0d0)
    f(1) = y(2)
    f(2) = -z * (z + 2d0 * tau * y(2))
  case (2)
    r2 = 1d0 / (rho * rho)
    f(1) = y(3)
    f(2) = y(4)
    f(3) = -y(1) * (1d0 + r2) - sigma * y(2) * (1d0 - r2)
    f(4) = -y(1) * (1d0 - r2) - sigma * y(2) * (1d0 + r2)
  case default
    z = max(y(1), 0d0)
    f(1) = y(2)
    f(2) = -z * sqrt(z)
  end select
end subroutine fcn

subroutine jac(n, x, y, dfy, ldfy, rpar, ipar)
  use problems
  implicit none
  integer :: n, ldfy, ipar(*)
  double precision :: x, y(n), dfy(ldfy, n), rpar(*), r2
  r2 = 1d0 / (rho * rho)
  dfy(1:4, 1:4) = 0d0
  dfy(1, 3) = 1d0
  dfy(2, 4) = 1d0
  dfy(3, 1) = -(1d0 + r2)
  dfy(3, 2) = -sigma * (1d0 - r2)
  dfy(4, 1) = -(1d0 - r2)
  dfy(4, 2) = -sigma * (1d0 + r2)
end subroutine jac

subroutine mas(n, am, lmas, rpar, ipar)
  implicit none
  integer :: n, lmas, ipar(*)
  double precision :: am(lmas, n), rpar(*)
end subroutine mas

subroutine solout(nr, xold, x, y, cont, lrc, n, rpar, ipar, irtrn)
  implicit none
  integer :: nr, lrc, n, ipar(*), irtrn
  double precision :: xold, x, y(n), cont(*), rpar(*)
end subroutine solout

subroutine solout8(nr, xold, x, y, n, con, icomp, nd, rpar, ipar, irtrn, xout)
  implicit none
  integer :: nr, n, nd, icomp(*), ipar(*), irtrn
  double precision :: xold, x, y(n), con(*), rpar(*), xout
end subroutine solout8

program driver
  use problems
  implicit none
  external fcn, jac, mas, solout, solout8
  character(len=32) :: arg, method, problem
  integer, parameter :: nmax = 4, lwork = nmax * (4 * nmax + 12) + 20 + 11 * nmax + 8 * nmax + 21
  integer, parameter :: liwork = 3 * nmax + 20 + nmax + 21
  double precision :: work(lwork), y(nmax), rtol(1), atol(1), x, h, t_end, tol, tin
  double precision, allocatable :: times(:)
  integer :: iwork(liwork), ipar(1), idid, n, repeats, k, r, ijac, ntol
  integer(8) :: c0, c1, rate
  double precision :: rpar(1)
  call get_command_argument(1, method)
  call get_command_argument(2, problem)
  call get_command_argument(3, arg); read (arg, *) t_end
  call get_command_argument(4, arg); read (arg, *) repeats
  ntol = command_argument_count() - 4
  allocate (times(repeats))
  select case (trim(problem))
  case ('cone'); which = 1; n = 2; ijac = 0
  case ('pendulum'); which = 2; n = 4; ijac = 1
  case default; which = 3; n = 2; ijac = 0
  end select
  call system_clock(count_rate=rate)
  do k = 1, ntol
    call get_command_argument(4 + k, arg); read (arg, *) tol
    do r = 1, repeats
      work = 0d0; iwork = 0
      select case (which)
      case (2); y(1:4) = (/0d0, 0d0, 0d0, 1d0/)
      case default; y(1:2) = (/0d0, 1d0/)
      end select
      x = 0d0
      call system_clock(c0)
      if (trim(method) == 'radau5') then
        tin = (10d0 * tol)**1.5d0
        if (tin <= 10d0 * 1d-16) then
          work(1) = 1d-18
          work(4) = max(10d0 * 1d-16 / tol, min(0.03d0, sqrt(tol)))
        end if
        rtol(1) = tin; atol(1) = tin; h = 1d-6
        call radau5(n, fcn, x, y, t_end, h, rtol, atol, 0, jac, ijac, n, n, mas, 0, n, n, &
                    solout, 0, .false., work, lwork, iwork, liwork, rpar, ipar, idid)
      else
        rtol(1) = tol; atol(1) = tol
        call dop853(n, fcn, x, y, t_end, rtol, atol, 0, solout8, 0, .false., work, lwork, &
                    iwork, liwork, rpar, ipar, idid)
      end if
      call system_clock(c1)
      times(r) = dble(c1 - c0) / dble(rate)
    end do
    call sort(times, repeats)
    if (trim(method) == 'radau5') then
      write (*, '(a,es10.3,a,i0,a,i0,a,i0,a,i0,a,i0,a,i0,a,es12.5,a,4(es24.16,:,","))', advance='no') &
        '{"tol": ', tol, ', "idid": ', idid, ', "rhs_evals": ', iwork(14), ', "jacobians": ', iwork(15), &
        ', "steps": ', iwork(17), ', "rejected": ', iwork(18), ', "lu_pairs": ', iwork(19), &
        ', "seconds": ', times((repeats + 1) / 2), ', "y": [', y(1:n)
    else
      write (*, '(a,es10.3,a,i0,a,i0,a,i0,a,i0,a,es12.5,a,4(es24.16,:,","))', advance='no') &
        '{"tol": ', tol, ', "idid": ', idid, ', "rhs_evals": ', iwork(17), ', "steps": ', iwork(19), &
        ', "rejected": ', iwork(20), ', "seconds": ', times((repeats + 1) / 2), ', "y": [', y(1:n)
    end if
    write (*, '(a)') ']}'
  end do
contains
  subroutine sort(a, m)
    integer :: m, i, j
    double precision :: a(m), v
    do i = 2, m
      v = a(i); j = i - 1
      do while (j >= 1)
        if (a(j) <= v) exit
        a(j + 1) = a(j); j = j - 1
      end do
      a(j + 1) = v
    end do
  end subroutine sort
end program driver
